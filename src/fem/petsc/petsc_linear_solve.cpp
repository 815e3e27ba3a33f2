#include "petsc_linear_solve.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>

#include "../conjugate_gradients.hpp"
#include "../morton_order.hpp"
#include "needlekit/core/errors.hpp"
#include "petsc_backend.hpp"

namespace needlekit::fem::detail {
namespace {

void check(PetscErrorCode code, const char* call) {
  if (code != 0) throw std::runtime_error(std::string("PETSc: ") + call + " failed with error " + std::to_string(code));
}

struct Ranks {
  PetscMPIInt rank = 0, size = 1;
};
Ranks ranks() {
  Ranks r;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r.rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &r.size);
  return r;
}

// The Chebyshev smoothers' interval from the estimated largest eigenvalue e: [0 e + 0.05 e, 0 e + 1.5 e] (PETSc's
// default is 0,0.1,0,1.1; create_solver says why).
constexpr const char* kChebyshevEstimateTransform = "0,0.05,0,1.5";

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
  partition_elements(inputs);
  collect_owned_rows();
  collect_sent_entries(inputs);
  k_ = create_matrix();
  if (matrix_.splits_preconditioner()) {  // the nodal average's patch term in the product, GAMG on P
    if (matrix_.preconditioner_values().size() != matrix_.values().size())
      throw std::logic_error("PETSc backend: P's pattern must be the element part's (tangent_layout)");
    p_ = create_matrix();
    patch_ = std::make_unique<PetscPatchOperator>(
        *inputs.nodal, inputs.free_index,
        PetscPatchOperator::Numbering{node_order_, row_of_dof_, first_row_, static_cast<PetscInt>(owned_rows_.size())},
        k_);
  }
  set_near_null_space(inputs);
  create_solver();
}

PetscLinearSolve::~PetscLinearSolve() {
  if (!PetscInitializeCalled || PetscFinalizeCalled) return;  // PETSc already gone with the process's session
  KSPDestroy(&ksp_);
  VecScatterDestroy(&gather_);
  VecDestroy(&gathered_);
  VecDestroy(&diagonal_);
  VecDestroy(&solution_);
  VecDestroy(&rhs_);
  patch_.reset();
  MatDestroy(&p_);
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
  const auto [rank, size] = ranks();
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

// The elements in the Morton order of their centroids, cut into one contiguous range of equal count per rank: the
// same cut for any thread count, and neighbouring elements mostly on one rank.
void PetscLinearSolve::partition_elements(const TangentInputs& in) {
  const size_t count = in.assembly_order.size();
  const auto npe = static_cast<size_t>(in.nodes_per_element);
  std::vector<Eigen::Vector3d> centroids(count, Eigen::Vector3d::Zero());
  for (size_t e = 0; e < count; ++e)
    for (size_t a = 0; a < npe; ++a)
      centroids[e] += in.nodes[static_cast<size_t>(in.connectivity[e * npe + a])] / static_cast<double>(npe);
  Eigen::Vector3d low = centroids.front(), high = low;
  for (const Eigen::Vector3d& x : centroids) low = low.cwiseMin(x), high = high.cwiseMax(x);
  const std::vector<int> order = morton_order(centroids, low, high);
  const auto [rank, size] = ranks();
  std::vector<char> mine(count, 0);
  const size_t first = static_cast<size_t>(rank) * count / static_cast<size_t>(size);
  const size_t last = static_cast<size_t>(rank + 1) * count / static_cast<size_t>(size);
  for (size_t position = first; position < last; ++position) mine[static_cast<size_t>(order[position])] = 1;
  assembled_.resize(count);
  for (size_t at = 0; at < count; ++at) assembled_[at] = mine[static_cast<size_t>(in.assembly_order[at])];
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
  std::vector<std::pair<PetscInt, int64_t>> sorted;  // each row in ascending column (write_owned_rows needs it)
  for (OwnedRow& row : owned_rows_) {
    sorted.clear();
    for (size_t j = 0; j < row.columns.size(); ++j) sorted.emplace_back(row.columns[j], row.positions[j]);
    std::sort(sorted.begin(), sorted.end());
    for (size_t j = 0; j < sorted.size(); ++j) std::tie(row.columns[j], row.positions[j]) = sorted[j];
  }
}

// The entries of this rank's elements that fall in rows of other ranks (at the partition's boundary): per element,
// its upper slots (tangent_matrix.hpp) in the element's dof order, each entry placed at (row, column) and its
// mirror (column, row).
void PetscLinearSolve::collect_sent_entries(const TangentInputs& in) {
  const int npe = in.nodes_per_element;
  const PetscInt owned_end = first_row_ + static_cast<PetscInt>(owned_rows_.size());
  const auto owned = [&](PetscInt row) { return row >= first_row_ && row < owned_end; };
  std::vector<std::tuple<int64_t, PetscInt, PetscInt>> sent;
  for (size_t at = 0; at < assembled_.size(); ++at) {
    if (!assembled_[at]) continue;
    const int* nodes = &in.connectivity[static_cast<size_t>(in.assembly_order[at]) * static_cast<size_t>(npe)];
    const auto row_of = [&](int local) { return row_of_dof_[3 * static_cast<size_t>(nodes[local / 3]) + local % 3]; };
    const int32_t* slot = matrix_.element_slots(at);
    for (int col = 0; col < 3 * npe; ++col)
      for (int row = 0; row <= col; ++row, ++slot) {
        if (*slot < 0) continue;
        const PetscInt a = row_of(row), b = row_of(col);
        if (!owned(a)) sent.emplace_back(*slot, a, b);
        if (a != b && !owned(b)) sent.emplace_back(*slot, b, a);
      }
  }
  std::sort(sent.begin(), sent.end());
  sent.erase(std::unique(sent.begin(), sent.end()), sent.end());
  for (const auto& [position, row, column] : sent) sent_entries_.push_back({position, row, column});
  sent_values_.assign(sent_entries_.size(), 0.0);
}

Mat PetscLinearSolve::create_matrix() {
  const PetscInt owned = static_cast<PetscInt>(owned_rows_.size());
  std::vector<PetscInt> diagonal_block(owned_rows_.size(), 0), off_diagonal_block(owned_rows_.size(), 0);
  for (size_t l = 0; l < owned_rows_.size(); ++l)
    for (PetscInt column : owned_rows_[l].columns)
      ++(column >= first_row_ && column < first_row_ + owned ? diagonal_block[l] : off_diagonal_block[l]);
  Mat m = nullptr;
  check(MatCreate(PETSC_COMM_WORLD, &m), "MatCreate");
  check(MatSetSizes(m, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(m, MATAIJ), "MatSetType");
  check(MatSetBlockSize(m, 3), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocation(m, 0, diagonal_block.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(m, 0, diagonal_block.data(), 0, off_diagonal_block.data()),
        "MatMPIAIJSetPreallocation");
  check(MatSetOption(m, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(m, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  if (solution_ == nullptr) {
    check(MatCreateVecs(m, &solution_, &rhs_), "MatCreateVecs");
    check(VecDuplicate(solution_, &diagonal_), "VecDuplicate");
    check(VecScatterCreateToAll(solution_, &gather_, &gathered_), "VecScatterCreateToAll");
  }
  return m;
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
  check(MatSetNearNullSpace(preconditioner_matrix(), rigid), "MatSetNearNullSpace");
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
  // GAMG's smoothers are Chebyshev on [0.1, 1.1] times the largest eigenvalue that a few Krylov iterations estimate.
  // Where the tissue under sharp tips is crushed (J ~ 0.15) the estimate falls short, the smoother amplifies the top
  // of the spectrum, and the preconditioner is indefinite (PETSc's DIVERGED_INDEFINITE_PC): every solve was then
  // shifted and Newton crawled. A margin of 1.5 keeps it definite (BENCHMARKS.md, "Why the array's deep steps
  // crawl"); -mg_levels_ksp_chebyshev_esteig on the command line overrides it.
  if (!option_given("-mg_levels_ksp_chebyshev_esteig"))
    check(PetscOptionsSetValue(nullptr, "-mg_levels_ksp_chebyshev_esteig", kChebyshevEstimateTransform),
          "PetscOptionsSetValue");
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  rtol_from_options_ = option_given("-ksp_rtol");
  reuse_from_options_ = option_given("-ksp_reuse_preconditioner");
}

void PetscLinearSolve::element_part_assembled() {
  const std::vector<double>& values = matrix_.values();
  for (size_t i = 0; i < sent_entries_.size(); ++i)
    sent_values_[i] = values[static_cast<size_t>(sent_entries_[i].position)];
}

void PetscLinearSolve::add_values() {
  add_values(k_, matrix_.values());
  if (!patch_) return;
  add_values(p_, matrix_.preconditioner_values());  // the same pattern (checked in the constructor)
  patch_->update();
}

// The owned rows of this rank's values (its elements' part, and the terms every rank has: contact, the patch term
// when K stores it, P's bulk term) and its elements' entries in other ranks' rows, added to the matrix (written
// straight into its arrays once an assembly has set its structure); MatAssemblyEnd sums them at their owners.
void PetscLinearSolve::add_values(Mat m, const std::vector<double>& values) {
  PetscBool structure_set = PETSC_FALSE;
  check(MatAssembled(m, &structure_set), "MatAssembled");
  if (structure_set)
    write_owned_rows(m, values);
  else
    set_owned_rows(m, values);
  for (size_t i = 0; i < sent_entries_.size(); ++i)
    check(MatSetValues(m, 1, &sent_entries_[i].row, 1, &sent_entries_[i].column, &sent_values_[i], ADD_VALUES),
          "MatSetValues");
  check(MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

// The first time: row by row through MatSetValues, which sets the matrix's structure (exactly the owned rows'
// entries: the preallocation).
void PetscLinearSolve::set_owned_rows(Mat m, const std::vector<double>& values) {
  check(MatZeroEntries(m), "MatZeroEntries");
  std::vector<PetscScalar> row_values;
  for (size_t l = 0; l < owned_rows_.size(); ++l) {
    const OwnedRow& row = owned_rows_[l];
    row_values.resize(row.columns.size());
    for (size_t j = 0; j < row.columns.size(); ++j)
      row_values[j] = row.positions[j] < 0 ? 1.0 : values[static_cast<size_t>(row.positions[j])];
    const PetscInt global = first_row_ + static_cast<PetscInt>(l);
    check(MatSetValues(m, 1, &global, static_cast<PetscInt>(row.columns.size()), row.columns.data(),
                       row_values.data(), ADD_VALUES),
          "MatSetValues");
  }
}

// Afterwards straight into the value arrays, without MatSetValues' search per entry (it was most of the assembly's
// overhead at 1.14 M tetrahedra, docs/scaling.md): this rank's rows are a diagonal block (the columns it owns) and
// an off-diagonal block (the others), two SeqAIJ matrices whose rows PETSc keeps in ascending column (the
// off-diagonal block's columns numbered in ascending global order), so an owned row's entries, sorted by column
// (collect_owned_rows), fill the two blocks' rows front to back. The blocks' sizes are checked against the rows.
// The assembly that follows (add_values) marks the matrix changed for the preconditioner's set-up.
void PetscLinearSolve::write_owned_rows(Mat m, const std::vector<double>& values) {
  PetscBool sequential = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m), MATSEQAIJ, &sequential), "PetscObjectTypeCompare");
  Mat diagonal = m, off_diagonal = nullptr;
  if (!sequential) check(MatMPIAIJGetSeqAIJ(m, &diagonal, &off_diagonal, nullptr), "MatMPIAIJGetSeqAIJ");
  PetscScalar *d = nullptr, *o = nullptr;
  check(MatSeqAIJGetArrayWrite(diagonal, &d), "MatSeqAIJGetArrayWrite");
  if (off_diagonal) check(MatSeqAIJGetArrayWrite(off_diagonal, &o), "MatSeqAIJGetArrayWrite");
  const PetscInt owned_end = first_row_ + static_cast<PetscInt>(owned_rows_.size());
  PetscInt in_diagonal = 0, in_off_diagonal = 0;
  for (const OwnedRow& row : owned_rows_)
    for (size_t j = 0; j < row.columns.size(); ++j) {
      const double value = row.positions[j] < 0 ? 1.0 : values[static_cast<size_t>(row.positions[j])];
      if (row.columns[j] >= first_row_ && row.columns[j] < owned_end)
        d[in_diagonal++] = value;
      else
        o[in_off_diagonal++] = value;
    }
  check(MatSeqAIJRestoreArrayWrite(diagonal, &d), "MatSeqAIJRestoreArrayWrite");
  if (off_diagonal) check(MatSeqAIJRestoreArrayWrite(off_diagonal, &o), "MatSeqAIJRestoreArrayWrite");
  MatInfo diagonal_info, off_diagonal_info{};
  check(MatGetInfo(diagonal, MAT_LOCAL, &diagonal_info), "MatGetInfo");
  if (off_diagonal) check(MatGetInfo(off_diagonal, MAT_LOCAL, &off_diagonal_info), "MatGetInfo");
  if (static_cast<PetscInt>(diagonal_info.nz_used) != in_diagonal ||
      static_cast<PetscInt>(off_diagonal_info.nz_used) != in_off_diagonal)
    throw std::logic_error("PETSc backend: the matrix's blocks do not hold the owned rows' entries");
}

// Rank 0 sums and sends the sums to every rank: all ranks get the same bits (an all-reduce may add in a different
// order on each rank), so that every rank's Newton loop takes the same branches.
void PetscLinearSolve::sum_over_processes(std::span<double> partial) {
  const auto [rank, size] = ranks();
  if (size == 1) return;
  const int count = static_cast<int>(partial.size());
  if (rank == 0)
    MPI_Reduce(MPI_IN_PLACE, partial.data(), count, MPI_DOUBLE, MPI_SUM, 0, PETSC_COMM_WORLD);
  else
    MPI_Reduce(partial.data(), nullptr, count, MPI_DOUBLE, MPI_SUM, 0, PETSC_COMM_WORLD);
  MPI_Bcast(partial.data(), count, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
}

int PetscLinearSolve::lowest_over_processes(int value) {
  int lowest = value;
  MPI_Allreduce(&value, &lowest, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  return lowest;
}

bool PetscLinearSolve::krylov_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                    double tolerance) {
  PetscScalar* b = nullptr;
  check(VecGetArray(rhs_, &b), "VecGetArray");
  for (size_t l = 0; l < owned_rows_.size(); ++l) b[l] = owned_rows_[l].free >= 0 ? rhs[owned_rows_[l].free] : 0.0;
  check(VecRestoreArray(rhs_, &b), "VecRestoreArray");
  check(KSPSetOperators(ksp_, patch_ ? patch_->operator_matrix() : k_, preconditioner_matrix()), "KSPSetOperators");
  if (!rtol_from_options_)
    check(KSPSetTolerances(ksp_, tolerance, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT), "KSPSetTolerances");
  check(KSPSolve(ksp_, rhs_, solution_), "KSPSolve");
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
  check(KSPGetConvergedReason(ksp_, &last_reason_), "KSPGetConvergedReason");
  rec.linear_iterations += static_cast<int>(iterations);
  last_iterations_ = static_cast<int>(iterations);
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

void PetscLinearSolve::keep_preconditioner(bool keep) {
  if (reuse_from_options_) return;
  check(KSPSetReusePreconditioner(ksp_, keep ? PETSC_TRUE : PETSC_FALSE), "KSPSetReusePreconditioner");
}

// CG with GAMG on K. GAMG's hierarchy is kept from one solve to the next while the last solve needed at most
// two_grid_refresh_iterations, as the built-in two-grid solve keeps its coarse operator: its set-up (aggregation and
// the Galerkin products) was 70 % of the solve time when it was redone for every solve (3 x 3 array benchmark,
// PETSc's -log_view: PCSetUp 2.68 s, KSPSolve 0.71 s on one rank). It is set up again when the last solve needed more,
// when CG fails on a kept one, and for a shifted K (record.factorized says when).
bool PetscLinearSolve::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing) {
  const double tolerance = std::max(forcing, options_.linear_tolerance);
  rec.linear_iterations = 0;
  add_values();
  if (shift_hint_ <= 0) {  // the last solve needed no shift, or the smallest: K is likely positive definite
    const bool keep = have_preconditioner_ && last_iterations_ <= options_.two_grid_refresh_iterations;
    rec.factorized = !keep;
    keep_preconditioner(keep);
    bool ok = krylov_solve(rhs, du, rec, tolerance);
    if (!ok && keep) {
      rec.factorized = true;
      keep_preconditioner(false);
      ok = krylov_solve(rhs, du, rec, tolerance);
    }
    have_preconditioner_ = ok;
    if (ok) {
      shift_hint_ = -1;
      return true;
    }
  }
  have_preconditioner_ = false;
  rec.factorized = true;
  keep_preconditioner(false);
  return shifted_solve(rhs, du, rec, tolerance);
}

// K not positive definite (CG met a direction of non-positive curvature, or did not converge): K's diagonal (and
// P's, when GAMG runs on P) is raised by the built-in solves' growing fractions (conjugate_gradients.hpp) until CG
// succeeds: a shifted Newton step is still a descent direction. As in the built-in two-grid solve, the next solve
// after a shift larger than the smallest starts one shift below the one that worked (shift_hint_), without the
// unshifted tries. The preconditioner built for a shifted K is not kept.
bool PetscLinearSolve::shifted_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                     double tolerance) {
  const Mat pre = preconditioner_matrix();
  check(MatGetDiagonal(pre, diagonal_), "MatGetDiagonal");
  Vec shifted = nullptr;
  check(VecDuplicate(diagonal_, &shifted), "VecDuplicate");
  bool ok = false;
  size_t shift = static_cast<size_t>(std::max(shift_hint_ - 1, 0));
  for (; shift < kDiagonalShifts.size() && !ok; ++shift) {
    check(VecCopy(diagonal_, shifted), "VecCopy");
    check(VecScale(shifted, 1 + kDiagonalShifts[shift]), "VecScale");
    check(MatDiagonalSet(pre, shifted, INSERT_VALUES), "MatDiagonalSet");
    if (patch_) patch_->set_shift(kDiagonalShifts[shift]);
    ok = krylov_solve(rhs, du, rec, tolerance);
  }
  if (patch_) patch_->set_shift(0);
  check(VecDestroy(&shifted), "VecDestroy");
  shift_hint_ = ok ? static_cast<int>(shift) - 1 : -1;
  return ok;
}

std::string PetscLinearSolve::failure_reason() const {
  return std::string("the tangent system could not be solved (PETSc KSP: ") + KSPConvergedReasons[last_reason_] +
         ", also with a diagonal shift)";
}

}  // namespace needlekit::fem::detail
