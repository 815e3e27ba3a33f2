// Internal: the PETSc backend's linear solve (linear_solve.hpp), K du = rhs across the ranks of MPI_COMM_WORLD with
// KSPCG preconditioned by PCGAMG and the rigid-body near-null space (docs/fem_solver.md, "PETSc backend").
//
// Every rank holds the same mesh and runs the same Newton loop; the element work and the solve are shared. The
// elements are cut by the Morton order of their centroids into contiguous ranges of equal count, one per rank (the
// same cut for any thread count); each rank assembles its own (assembled_elements), and the assembly sums the
// partial energy and forces over the ranks. The PETSc matrix is over all dofs, 3 per node (block size 3: GAMG
// aggregates nodes and the rigid-body modes are per node), the nodes in Morton order and cut into contiguous ranges
// of equal size, one per rank; a prescribed dof is an identity row and column, so that the free rows are K's. It is
// a MatMPIAIJ preallocated exactly from K's pattern. Each rank adds (ADD_VALUES) its elements' entries of the rows it
// owns together with the terms every rank computes alike (contact: added once, by the owner of the row), and its
// elements' entries of other ranks' rows, which PETSc sends to their owners in MatAssemblyEnd. With the nodal
// average, that matrix is the one-ring element part A, a second one P = A + the element bulk term (the built-in
// split preconditioner's bound of K) is GAMG's, and CG runs on K = A + G D G^T applied as a shell
// (petsc_patch_operator.hpp). PETSc solves, and the solution is gathered to every rank (VecScatterCreateToAll).
// Options: KSPCG, PCGAMG, relative tolerance the Newton forcing term on the unpreconditioned residual (the built-in
// solves' test); -ksp_* / -pc_* on the command line override them (KSPSetFromOptions).
#pragma once
#include <petscksp.h>

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "../linear_solve.hpp"
#include "petsc_patch_operator.hpp"

namespace needlekit::fem::detail {

class PetscLinearSolve final : public LinearSolve {
public:
  PetscLinearSolve(TangentMatrix& matrix, const TangentInputs& inputs, const SolverOptions& options);
  ~PetscLinearSolve() override;
  PetscLinearSolve(const PetscLinearSolve&) = delete;
  PetscLinearSolve& operator=(const PetscLinearSolve&) = delete;

  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double forcing) override;
  std::string failure_reason() const override;
  double factor_nonzeros() const override { return 0; }  // no Cholesky factor
  double factor_flops() const override { return 0; }
  const std::vector<char>& assembled_elements() const override { return assembled_; }
  void sum_over_processes(std::span<double> partial) override;
  int lowest_over_processes(int value) override;
  void element_part_assembled() override;

private:
  // One owned row of K: its free index (-1: a prescribed dof, an identity row), and its entries as PETSc columns
  // with their positions in the tangent's values.
  struct OwnedRow {
    int free = -1;
    std::vector<PetscInt> columns;
    std::vector<int64_t> positions;
  };
  // An entry of this rank's elements in another rank's row: its position in the tangent's values, its PETSc place.
  struct SentEntry {
    int64_t position;
    PetscInt row, column;
  };
  void number_dofs(const TangentInputs& inputs);
  void partition_elements(const TangentInputs& inputs);
  void collect_owned_rows();
  void collect_sent_entries(const TangentInputs& inputs);
  Mat create_matrix();  // preallocated for the owned rows' pattern (and the solver's vectors, on the first call)
  Mat preconditioner_matrix() const { return patch_ ? p_ : k_; }
  void set_near_null_space(const TangentInputs& inputs);
  void create_solver();
  void add_values();  // this rank's part of the tangent's current values into k_ (and p_, G and D)
  void add_values(Mat m, const std::vector<double>& values);
  void set_owned_rows(Mat m, const std::vector<double>& values);
  void write_owned_rows(Mat m, const std::vector<double>& values);
  bool krylov_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double tolerance);
  void keep_preconditioner(bool keep);  // KSPSetReusePreconditioner, unless -ksp_reuse_preconditioner is given
  bool shifted_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double tolerance);

  // CG iterations before a solve counts as failed (and K's diagonal is shifted): the built-in two-grid solve's
  // budget. At 1000, a tangent that was not positive definite cost minutes per try on a 627k-tetrahedron quarter
  // array before its shift.
  static constexpr PetscInt kMaxIterations = 200;

  TangentMatrix& matrix_;
  const SolverOptions& options_;
  std::vector<int> node_order_;       // the nodes in Morton order: PETSc's node blocks
  std::vector<PetscInt> row_of_dof_;  // per dof (3 * node + component): its PETSc row
  std::vector<int> dof_of_free_;      // per free index: its dof
  PetscInt first_row_ = 0;            // the rows [first_row_, first_row_ + owned_rows_.size()) are this rank's
  std::vector<OwnedRow> owned_rows_;
  std::vector<char> assembled_;          // per position of the assembly order: whether this rank assembles it
  std::vector<SentEntry> sent_entries_;  // this rank's element entries in rows of other ranks
  std::vector<double> sent_values_;      // their element part, kept by element_part_assembled
  Mat k_ = nullptr;  // K, or with the nodal average's patch term in the product its element part A
  Mat p_ = nullptr;  // with the patch term in the product: P = A + the element bulk term, GAMG's matrix
  std::unique_ptr<PetscPatchOperator> patch_;  // with the patch term in the product: K = A + G D G^T as a shell
  Vec rhs_ = nullptr, solution_ = nullptr, gathered_ = nullptr, diagonal_ = nullptr;
  VecScatter gather_ = nullptr;
  KSP ksp_ = nullptr;
  bool rtol_from_options_ = false;  // -ksp_rtol given: it replaces the Newton forcing term
  bool reuse_from_options_ = false;  // -ksp_reuse_preconditioner given: it replaces the refresh rule below
  bool have_preconditioner_ = false;  // the preconditioner was set up for an unshifted K and may be kept
  int shift_hint_ = -1;     // index into kDiagonalShifts of the last shifted solve's shift, -1: none was needed
  int last_iterations_ = 0;           // Krylov iterations of the last solve (what keeping the hierarchy looks at)
  KSPConvergedReason last_reason_ = KSP_CONVERGED_ITERATING;
};

}  // namespace needlekit::fem::detail
