// Internal: the PETSc backend's linear solve (linear_solve.hpp), K du = rhs across the ranks of MPI_COMM_WORLD with
// KSPCG preconditioned by PCGAMG and the rigid-body near-null space (docs/fem_solver.md, "PETSc backend").
//
// Every rank holds the same mesh and tangent (the Newton loop is replicated). The PETSc matrix is over all dofs,
// 3 per node (block size 3: GAMG aggregates nodes and the rigid-body modes are per node), the nodes in Morton order
// and cut into contiguous ranges of equal size, one per rank; a prescribed dof is an identity row and column, so that
// the free rows are K's. Each rank inserts the rows it owns (preallocated exactly), PETSc solves, and the solution
// is gathered to every rank (VecScatterCreateToAll). Options: KSPCG, PCGAMG, relative tolerance the Newton forcing
// term on the unpreconditioned residual (the built-in solves' test); -ksp_* / -pc_* on the command line override
// them (KSPSetFromOptions).
#pragma once
#include <petscksp.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "../linear_solve.hpp"

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

private:
  // One owned row of K: its free index (-1: a prescribed dof, an identity row), and its entries as PETSc columns
  // with their positions in the tangent's values.
  struct OwnedRow {
    int free = -1;
    std::vector<PetscInt> columns;
    std::vector<int64_t> positions;
  };
  void number_dofs(const TangentInputs& inputs);
  void collect_owned_rows();
  void create_matrix();
  void set_near_null_space(const TangentInputs& inputs);
  void create_solver();
  void insert_values();  // the owned rows of the tangent's current values into k_
  bool krylov_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double tolerance);

  static constexpr PetscInt kMaxIterations = 1000;

  TangentMatrix& matrix_;
  const SolverOptions& options_;
  std::vector<int> node_order_;       // the nodes in Morton order: PETSc's node blocks
  std::vector<PetscInt> row_of_dof_;  // per dof (3 * node + component): its PETSc row
  std::vector<int> dof_of_free_;      // per free index: its dof
  PetscInt first_row_ = 0;            // the rows [first_row_, first_row_ + owned_rows_.size()) are this rank's
  std::vector<OwnedRow> owned_rows_;
  Mat k_ = nullptr;
  Vec rhs_ = nullptr, solution_ = nullptr, gathered_ = nullptr;
  VecScatter gather_ = nullptr;
  KSP ksp_ = nullptr;
  bool rtol_from_options_ = false;  // -ksp_rtol given: it replaces the Newton forcing term
  KSPConvergedReason last_reason_ = KSP_CONVERGED_ITERATING;
};

}  // namespace needlekit::fem::detail
