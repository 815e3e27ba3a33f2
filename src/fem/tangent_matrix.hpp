// Internal: the free-dof tangent stiffness K of the quasi-static solver as the assembly fills it: its symmetric
// sparse pattern (upper triangle, sparse_pattern.hpp), its values, the per-element slot table the assembly adds
// through, and the product y = K x (symmetric_product.hpp). The linear solves (linear_solve.hpp) read it.
//
// The nodal-averaged tetrahedron (nodal_volume.hpp) couples node patches: K's pattern is then the mesh's two-ring.
// Two layouts avoid factorizing that two-ring matrix (TangentLayout):
//  - the patch term in the product: K is stored as its one-ring element part A alone and the product adds the patch
//    term G D G^T x (the two-grid solve, nodal_volume_preconditioner.hpp);
//  - a one-ring preconditioner matrix P next to the two-ring K (the split preconditioner of
//    split_preconditioned_solve.hpp): capture_preconditioner() copies K's one-ring entries as assembled so far into
//    P, and the assembly then adds a per-element bulk term through preconditioner_slot().
// The PETSc backend takes both: the patch term in the product and P, on the one-ring pattern of A, for GAMG
// (petsc/petsc_patch_operator.hpp).
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "nodal_volume.hpp"
#include "sparse_pattern.hpp"
#include "symmetric_product.hpp"
#include "tangent_inputs.hpp"

namespace needlekit::fem::detail {

// How K holds the nodal average's patch term (see above); both false without a nodal average.
struct TangentLayout {
  bool patch_term_in_product = false;  // K stores the one-ring part A; the product adds G D G^T x
  bool one_ring_preconditioner = false;  // P: the one-ring bound of K (with the patch term stored: K two-ring)
};

class TangentMatrix {
public:
  TangentMatrix(const TangentInputs& inputs, const TangentLayout& layout, tbb::task_arena& arena);

  // The stored upper-triangle entries; assembly adds into them (zero() first).
  std::vector<double>& values() { return values_; }
  const std::vector<double>& values() const { return values_; }
  void zero() { std::fill(values_.begin(), values_.end(), 0.0); }
  const UpperPattern& pattern() const { return pattern_; }
  int64_t free_count() const { return static_cast<int64_t>(pattern_.column_pointers.size()) - 1; }
  SymmetricProduct& product() { return *product_; }
  // Per element, the upper triangle of the (symmetric) element matrix in column-major order, (row, col) for
  // row <= col < 3N: the index into values() of the global entry (min, max) of their free dofs, -1 if either dof is
  // prescribed. Assembly adds without searching or branching on the global order, and reads half the slots a full
  // (3N)^2 table would.
  static constexpr int upper_slots(int element_dofs) { return element_dofs * (element_dofs + 1) / 2; }
  // The slots of the element at `position` of the assembly order.
  const int32_t* element_slots(size_t position) const { return &value_slot_[position * slots_per_element_]; }

  // y = K x (with the patch term in the product: the stored element part plus G D G^T x).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y);
  // ys[i] = K xs[i] for every i (one pass over the stored values per SymmetricProduct::kMaxBlock vectors).
  void multiply(std::span<const Eigen::VectorXd* const> xs, std::span<Eigen::VectorXd* const> ys);

  // Whether K's stored values hold the nodal average's patch term (assembled by NodalVolumeAverage::
  // add_patch_tangent); with the patch term in the product they do not.
  bool stores_patch_term() const { return patch_term_ == nullptr; }
  // The one-ring preconditioner P (see above).
  bool splits_preconditioner() const { return !full_to_pre_.empty(); }
  void capture_preconditioner();
  std::vector<double>& preconditioner_values() { return pre_values_; }
  const UpperPattern& preconditioner_pattern() const { return pre_pattern_; }
  int32_t preconditioner_slot(int32_t slot) const { return full_to_pre_[static_cast<size_t>(slot)]; }

private:
  void fill_element_slots(const TangentInputs& inputs);
  void map_preconditioner_entries(const TangentInputs& inputs);
  void add_patch_product(const Eigen::VectorXd& x, Eigen::VectorXd& y);  // y += G D G^T x

  tbb::task_arena& arena_;
  const std::vector<int>& free_index_;
  const NodalVolumeAverage* patch_term_ = nullptr;  // the nodal average whose patch term K leaves to the product
  Eigen::VectorXd patch_values_;                    // one per node: D G^T x
  UpperPattern pattern_;
  std::vector<double> values_;
  std::unique_ptr<SymmetricProduct> product_;  // on pattern_ (a pointer: pattern_ is set in the constructor's body)
  size_t slots_per_element_ = 0;
  std::vector<int32_t> value_slot_;
  // One-ring preconditioner: P's pattern and values, per entry of values_ its entry in P (-1: none).
  UpperPattern pre_pattern_;
  std::vector<double> pre_values_;
  std::vector<int32_t> full_to_pre_;
};

}  // namespace needlekit::fem::detail
