#include "petsc_linear_solve.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "../conjugate_gradients.hpp"
#include "../morton_order.hpp"
#include "needlekit/core/errors.hpp"
#include "petsc_backend.hpp"

namespace needlekit::fem::detail {
namespace {

void check(PetscErrorCode code, const char* call) {
  if (code != 0) throw std::runtime_error(std::string("PETSc: ") + call + " failed with error " + std::to_string(code));
}

// Whether the command line (or PETSC_OPTIONS) sets this option: then it overrides the solver's own choice.
bool option_given(const char* name) {
  PetscBool given = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &given), "PetscOptionsHasName");
  return given == PETSC_TRUE;
}

}  // namespace

std::unique_ptr<LinearSolve> make_petsc_linear_solve(TangentMatrix& matrix, const TangentInputs& inputs,
                                                     const SolverOptions& options) {
  start_petsc();
  return std::make_unique<PetscLinearSolve>(matrix, inputs, options);
}

PetscLinearSolve::PetscLinearSolve(TangentMatrix& matrix, const TangentInputs& inputs, const SolverOptions& options)
    : matrix_(matrix), options_(options) {
  number_dofs(inputs);
  collect_owned_rows();
  create_matrix();
  set_near_null_space(inputs);
  create_solver();
}

PetscLinearSolve::~PetscLinearSolve() {
  if (!PetscInitializeCalled || PetscFinalizeCalled) return;  // PETSc already gone with the process's session
  KSPDestroy(&ksp_);
  VecScatterDestroy(&gather_);
  VecDestroy(&gathered_);
  VecDestroy(&solution_);
  VecDestroy(&rhs_);
  MatDestroy(&k_);
}

// The nodes in Morton order, cut into one contiguous range per rank: rank r owns the positions
// [r n / size, (r + 1) n / size) and their 3 dofs each.
void PetscLinearSolve::number_dofs(const TangentInputs& in) {
  Eigen::Vector3d low = in.nodes.front(), high = low;
  for (const Eigen::Vector3d& x : in.nodes) low = low.cwiseMin(x), high = high.cwiseMax(x);
  node_order_ = morton_order(in.nodes, low, high);
  row_of_dof_.assign(3 * in.nodes.size(), 0);
  for (size_t position = 0; position < node_order_.size(); ++position)
    for (int i = 0; i < 3; ++i)
      row_of_dof_[3 * static_cast<size_t>(node_order_[position]) + i] = static_cast<PetscInt>(3 * position + i);
  dof_of_free_.assign(static_cast<size_t>(matrix_.free_count()), -1);
  for (size_t dof = 0; dof < in.free_index.size(); ++dof)
    if (in.free_index[dof] >= 0) dof_of_free_[static_cast<size_t>(in.free_index[dof])] = static_cast<int>(dof);
  PetscMPIInt rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const int64_t n = static_cast<int64_t>(in.nodes.size());
  const int64_t first = rank * n / size, last = (rank + 1) * n / size;
  if (last == first)
    throw InvalidInput("mpirun: " + std::to_string(size) + " ranks for a mesh of " + std::to_string(n) +
                       " nodes, expected at most one rank per node");
  first_row_ = static_cast<PetscInt>(3 * first);
  owned_rows_.assign(static_cast<size_t>(3 * (last - first)), OwnedRow{});
  for (size_t l = 0; l < owned_rows_.size(); ++l) {
    const size_t row = static_cast<size_t>(first_row_) + l;
    owned_rows_[l].free = in.free_index[3 * static_cast<size_t>(node_order_[row / 3]) + row % 3];
  }
}

// K's upper triangle mirrored into the full rows this rank owns; a prescribed dof's row is the identity.
void PetscLinearSolve::collect_owned_rows() {
  const UpperPattern& pattern = matrix_.pattern();
  const auto row_of_free = [&](int64_t f) { return row_of_dof_[static_cast<size_t>(dof_of_free_[f])]; };
  const auto add = [&](PetscInt row, PetscInt column, int64_t position) {
    const PetscInt local = row - first_row_;
    if (local < 0 || local >= static_cast<PetscInt>(owned_rows_.size())) return;
    owned_rows_[static_cast<size_t>(local)].columns.push_back(column);
    owned_rows_[static_cast<size_t>(local)].positions.push_back(position);
  };
  for (int64_t c = 0; c < matrix_.free_count(); ++c)
    for (int64_t k = pattern.column_pointers[static_cast<size_t>(c)];
         k < pattern.column_pointers[static_cast<size_t>(c) + 1]; ++k) {
      const int64_t r = pattern.row_indices[static_cast<size_t>(k)];
      add(row_of_free(r), row_of_free(c), k);
      if (r != c) add(row_of_free(c), row_of_free(r), k);
    }
  for (size_t l = 0; l < owned_rows_.size(); ++l)
    if (owned_rows_[l].free < 0) add(first_row_ + static_cast<PetscInt>(l), first_row_ + static_cast<PetscInt>(l), -1);
}

void PetscLinearSolve::create_matrix() {
  const PetscInt owned = static_cast<PetscInt>(owned_rows_.size());
  std::vector<PetscInt> diagonal_block(owned_rows_.size(), 0), off_diagonal_block(owned_rows_.size(), 0);
  for (size_t l = 0; l < owned_rows_.size(); ++l)
    for (PetscInt column : owned_rows_[l].columns)
      ++(column >= first_row_ && column < first_row_ + owned ? diagonal_block[l] : off_diagonal_block[l]);
  check(MatCreate(PETSC_COMM_WORLD, &k_), "MatCreate");
  check(MatSetSizes(k_, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(k_, MATAIJ), "MatSetType");
  check(MatSetBlockSize(k_, 3), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocation(k_, 0, diagonal_block.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(k_, 0, diagonal_block.data(), 0, off_diagonal_block.data()),
        "MatMPIAIJSetPreallocation");
  check(MatSetOption(k_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(k_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  check(MatCreateVecs(k_, &solution_, &rhs_), "MatCreateVecs");
  check(VecScatterCreateToAll(solution_, &gather_, &gathered_), "VecScatterCreateToAll");
}

// The six rigid-body modes from the reference coordinates of the owned nodes (GAMG's near-null space for elasticity).
void PetscLinearSolve::set_near_null_space(const TangentInputs& in) {
  Vec coordinates = nullptr;
  check(VecDuplicate(solution_, &coordinates), "VecDuplicate");
  PetscScalar* x = nullptr;
  check(VecGetArray(coordinates, &x), "VecGetArray");
  for (size_t l = 0; l < owned_rows_.size(); ++l) {
    const size_t row = static_cast<size_t>(first_row_) + l;
    x[l] = in.nodes[static_cast<size_t>(node_order_[row / 3])][static_cast<Eigen::Index>(row % 3)];
  }
  check(VecRestoreArray(coordinates, &x), "VecRestoreArray");
  MatNullSpace rigid = nullptr;
  check(MatNullSpaceCreateRigidBody(coordinates, &rigid), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(k_, rigid), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&rigid), "MatNullSpaceDestroy");
  check(VecDestroy(&coordinates), "VecDestroy");
}

void PetscLinearSolve::create_solver() {
  check(KSPCreate(PETSC_COMM_WORLD, &ksp_), "KSPCreate");
  check(KSPSetType(ksp_, KSPCG), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  check(KSPSetTolerances(ksp_, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, kMaxIterations), "KSPSetTolerances");
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  rtol_from_options_ = option_given("-ksp_rtol");
}

void PetscLinearSolve::insert_values() {
  const std::vector<double>& values = matrix_.values();
  std::vector<PetscScalar> row_values;
  for (size_t l = 0; l < owned_rows_.size(); ++l) {
    const OwnedRow& row = owned_rows_[l];
    row_values.resize(row.columns.size());
    for (size_t j = 0; j < row.columns.size(); ++j)
      row_values[j] = row.positions[j] < 0 ? 1.0 : values[static_cast<size_t>(row.positions[j])];
    const PetscInt global = first_row_ + static_cast<PetscInt>(l);
    check(MatSetValues(k_, 1, &global, static_cast<PetscInt>(row.columns.size()), row.columns.data(),
                       row_values.data(), INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

bool PetscLinearSolve::krylov_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                    double tolerance) {
  PetscScalar* b = nullptr;
  check(VecGetArray(rhs_, &b), "VecGetArray");
  for (size_t l = 0; l < owned_rows_.size(); ++l) b[l] = owned_rows_[l].free >= 0 ? rhs[owned_rows_[l].free] : 0.0;
  check(VecRestoreArray(rhs_, &b), "VecRestoreArray");
  check(KSPSetOperators(ksp_, k_, k_), "KSPSetOperators");
  if (!rtol_from_options_)
    check(KSPSetTolerances(ksp_, tolerance, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT), "KSPSetTolerances");
  check(KSPSolve(ksp_, rhs_, solution_), "KSPSolve");
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
  check(KSPGetConvergedReason(ksp_, &last_reason_), "KSPGetConvergedReason");
  rec.linear_iterations += static_cast<int>(iterations);
  if (last_reason_ <= 0) return false;
  check(VecScatterBegin(gather_, solution_, gathered_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(gather_, solution_, gathered_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* x = nullptr;
  check(VecGetArrayRead(gathered_, &x), "VecGetArrayRead");
  du.resize(static_cast<Eigen::Index>(dof_of_free_.size()));
  for (size_t f = 0; f < dof_of_free_.size(); ++f)
    du[static_cast<Eigen::Index>(f)] = x[row_of_dof_[static_cast<size_t>(dof_of_free_[f])]];
  check(VecRestoreArrayRead(gathered_, &x), "VecRestoreArrayRead");
  return du.allFinite();
}

// CG with GAMG on K; if CG fails (K not positive definite: it meets a direction of non-positive curvature), K's
// diagonal is raised by the built-in solves' growing fractions (conjugate_gradients.hpp) until it succeeds: a shifted
// Newton step is still a descent direction. The preconditioner is set up again for every solve (record.factorized).
bool PetscLinearSolve::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing) {
  const double tolerance = std::max(forcing, options_.linear_tolerance);
  rec.factorized = true;
  rec.linear_iterations = 0;
  insert_values();
  if (krylov_solve(rhs, du, rec, tolerance)) return true;
  std::vector<double>& values = matrix_.values();
  const std::vector<double> unshifted = values;
  bool ok = false;
  for (size_t shift = 0; shift < kDiagonalShifts.size() && !ok; ++shift) {
    shift_diagonal(matrix_.pattern(), unshifted, kDiagonalShifts[shift], values);
    insert_values();
    ok = krylov_solve(rhs, du, rec, tolerance);
  }
  values = unshifted;
  return ok;
}

std::string PetscLinearSolve::failure_reason() const {
  return std::string("the tangent system could not be solved (PETSc KSP: ") + KSPConvergedReasons[last_reason_] +
         ", also with a diagonal shift)";
}

}  // namespace needlekit::fem::detail
