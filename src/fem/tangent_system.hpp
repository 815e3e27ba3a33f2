// Internal: the free-dof tangent stiffness K of the quasi-static solver and the solution of K du = rhs — its
// symmetric sparse product (symmetric_product.hpp), preconditioned conjugate gradients with Krylov
// recycling, and the choice between a fresh CHOLMOD factorization, CG on the last one (Cholesky-CG) and CG with the
// two-grid cycle.
//
// Split preconditioner (Cholesky-CG with node groups, i.e. the nodal-averaged tetrahedron of nodal_volume.hpp): the
// groups make K's pattern the mesh's two-ring, whose Cholesky factor costs several times the one-ring's (measured 8x
// the CPU of a Newton solve on the §6.2 phantom). CG then runs on the full K, preconditioned by the factor of a
// one-ring matrix P that the assembly provides (capture_preconditioner + preconditioner_values: the element part of K
// plus a per-element bulk term that bounds the nodal one from above). If CG on a fresh factor of P still fails (K not
// positive definite), both diagonals are shifted, as in the two-grid solve. With a coarse level (TwoGrid) K is
// stored as its one-ring element part A alone, the product adds the patch term G D G^T x, and CG is preconditioned
// without a fine factor (nodal_volume_preconditioner.hpp).
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/mesh/coarse_level.hpp"
#include "nodal_volume.hpp"
#include "nodal_volume_preconditioner.hpp"
#include "sparse_cholesky.hpp"
#include "sparse_pattern.hpp"
#include "symmetric_product.hpp"
#include "two_grid_preconditioner.hpp"

namespace needlekit::fem::detail {

class TangentSystem {
public:
  // `connectivity`: nodes_per_element node indices per element; `free_index`: per dof its free index or -1;
  // `solver`: resolved (not Automatic); `coarse`: the two-grid solver's coarse level (TwoGrid only).
  // `nodal`: the nodal volume average of linear elements, whose node patches couple (upper_pattern), or null.
  // `assembly_order`: every element once, in the order the assembly visits them (ElementColouring::elements); the
  // slot table is stored in that order, so the assembly reads it front to back.
  TangentSystem(const std::vector<int>& connectivity, int nodes_per_element, int node_count,
                const std::vector<int>& free_index, const std::vector<int>& assembly_order, LinearSolver solver,
                const mesh::CoarseLevel* coarse, const SolverOptions& options, tbb::task_arena& arena,
                const NodalVolumeAverage* nodal = nullptr);

  // The stored upper-triangle entries; assembly adds into them (zero() first).
  std::vector<double>& values() { return values_; }
  void zero() { std::fill(values_.begin(), values_.end(), 0.0); }
  const UpperPattern& pattern() const { return pattern_; }
  // Per element, the upper triangle of the (symmetric) element matrix in column-major order, (row, col) for
  // row <= col < 3N: the index into values() of the global entry (min, max) of their free dofs, -1 if either dof is
  // prescribed. Assembly adds without searching or branching on the global order, and reads half the slots a full
  // (3N)^2 table would.
  static constexpr int upper_slots(int element_dofs) { return element_dofs * (element_dofs + 1) / 2; }
  // The slots of the element at `position` of the assembly order.
  const int32_t* element_slots(size_t position) const { return &value_slot_[position * slots_per_element_]; }

  // y = K x (with the two-grid solver and a nodal average: the stored element part plus G D G^T x).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y);
  // Solves K du = rhs to the relative residual `forcing` (inexact Newton; never tighter than linear_tolerance).
  // Records CG iterations and whether a factorization was taken in `record`. False if K could not be solved.
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double forcing);

  // Split preconditioner (see above): P's values on the one-ring pattern. capture_preconditioner() sets them to the
  // one-ring entries of values() as assembled so far; the bulk term is then added through
  // preconditioner_slot(), which maps an element slot of values() to P's entry.
  bool splits_preconditioner() const { return !full_to_pre_.empty(); }
  // Whether K's stored values hold the nodal average's patch term (assembled by NodalVolumeAverage::
  // add_patch_tangent); with the two-grid solver they do not: the product adds it (multiply()).
  bool stores_patch_term() const { return patch_term_ == nullptr; }
  void capture_preconditioner();
  std::vector<double>& preconditioner_values() { return pre_values_; }
  int32_t preconditioner_slot(int32_t slot) const { return full_to_pre_[static_cast<size_t>(slot)]; }

  LinearSolver solver() const { return solver_; }
  double factor_nonzeros() const;
  double factor_flops() const;

private:
  bool cholesky_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing);
  bool two_grid_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing);
  bool split_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing);
  template <class Prepare, class Preconditioner>
  bool cycle_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing,
                   Prepare&& prepare, Preconditioner&& precondition);
  // Factorizes `values` (on `cholesky`'s pattern), raising the diagonal by growing fractions if it is not positive
  // definite (a shifted Newton step is still a descent direction). False if even the largest shift fails.
  bool factorize_or_shift(SparseCholesky& cholesky, const std::vector<double>& values, const UpperPattern& pattern);
  int cg_budget() const;
  Eigen::VectorXd apply_factor(const Eigen::VectorXd& r);
  void add_patch_product(const Eigen::VectorXd& x, Eigen::VectorXd& y);  // y += G D G^T x
  void remember(const Eigen::VectorXd& solution);
  void recycled_start(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, Eigen::VectorXd& r);
  template <class Preconditioner>
  bool cg_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int& iterations, double tolerance, int budget,
                Preconditioner&& precondition);
  template <class Refresh, class Preconditioner>
  bool shifted_cg_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double tolerance,
                        int budget, int& iterations, Refresh&& refresh, Preconditioner&& precondition, int first = 0);
  static void shift_diagonal(const UpperPattern& pattern, const std::vector<double>& base, double beta,
                             std::vector<double>& shifted);

  const SolverOptions& options_;
  tbb::task_arena& arena_;
  LinearSolver solver_;
  const std::vector<int>& free_index_;
  const NodalVolumeAverage* patch_term_ = nullptr;  // the nodal average whose patch term K leaves to the product
  Eigen::VectorXd patch_values_;                    // one per node: D G^T x
  UpperPattern pattern_;
  std::vector<double> values_;
  std::unique_ptr<SymmetricProduct> product_;  // on pattern_ (a pointer: pattern_ is set in the constructor's body)
  size_t slots_per_element_ = 0;
  std::vector<int32_t> value_slot_;
  std::unique_ptr<SparseCholesky> cholesky_;         // Cholesky, CholeskyCg (of P with the split preconditioner)
  // Split preconditioner: P's one-ring pattern and values, per entry of values_ its entry in P (-1: none).
  UpperPattern pre_pattern_;
  std::vector<double> pre_values_;
  std::vector<int32_t> full_to_pre_;
  int fresh_cg_iterations_ = 0;  // of the last solve on a fresh factor of P
  std::unique_ptr<TwoGridPreconditioner> two_grid_;  // TwoGrid
  std::unique_ptr<NodalVolumePreconditioner> nodal_two_grid_;  // TwoGrid with the nodal volume average
  bool have_factor_ = false;
  int last_cg_iterations_ = 0;  // of the last CG solve
  int shift_hint_ = -1;         // index into the diagonal shifts of the last solve's shift, -1: it needed none
  // Krylov recycling: unit vectors of the last solutions (newest last) and K times each (recomputed per solve).
  std::vector<Eigen::VectorXd> recycled_, recycled_products_;
};

}  // namespace needlekit::fem::detail
