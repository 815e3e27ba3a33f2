#include "petsc_patch_operator.hpp"

#include <initializer_list>
#include <stdexcept>
#include <string>

namespace needlekit::fem::detail {
namespace {

void check(PetscErrorCode code, const char* call) {
  if (code != 0) throw std::runtime_error(std::string("PETSc: ") + call + " failed with error " + std::to_string(code));
}

}  // namespace

PetscPatchOperator::PetscPatchOperator(const NodalVolumeAverage& nodal, const std::vector<int>& free_index,
                                       const Numbering& numbering, Mat element_part)
    : nodal_(nodal), free_index_(free_index), numbering_(numbering), element_part_(element_part) {
  position_of_node_.assign(numbering.node_order.size(), 0);
  for (size_t position = 0; position < numbering.node_order.size(); ++position)
    position_of_node_[static_cast<size_t>(numbering.node_order[position])] = static_cast<PetscInt>(position);
  const PetscInt owned_nodes = numbering.owned_rows / 3, first_node = numbering.first_row / 3;
  const std::vector<int>& pointers = nodal.patch_pointers();
  const std::vector<int>& patch = nodal.patch_nodes();
  std::vector<PetscInt> diagonal_block(static_cast<size_t>(numbering.owned_rows), 0);
  std::vector<PetscInt> off_diagonal_block(static_cast<size_t>(numbering.owned_rows), 0);
  for (PetscInt l = 0; l < numbering.owned_rows; ++l) {
    const PetscInt b = owned_row_node(l);
    for (int k = pointers[static_cast<size_t>(b)]; k < pointers[static_cast<size_t>(b) + 1]; ++k) {
      const PetscInt column = position_of_node_[static_cast<size_t>(patch[static_cast<size_t>(k)])];
      ++(column >= first_node && column < first_node + owned_nodes ? diagonal_block : off_diagonal_block)[l];
    }
  }
  check(MatCreate(PETSC_COMM_WORLD, &gradients_), "MatCreate");
  check(MatSetSizes(gradients_, numbering.owned_rows, owned_nodes, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(gradients_, MATAIJ), "MatSetType");
  check(MatSeqAIJSetPreallocation(gradients_, 0, diagonal_block.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(gradients_, 0, diagonal_block.data(), 0, off_diagonal_block.data()),
        "MatMPIAIJSetPreallocation");
  check(MatCreateVecs(gradients_, &node_values_, &shift_), "MatCreateVecs");
  check(VecDuplicate(node_values_, &curvature_), "VecDuplicate");
  check(VecDuplicate(shift_, &shifted_), "VecDuplicate");
  check(MatCreateShell(PETSC_COMM_WORLD, numbering.owned_rows, numbering.owned_rows, PETSC_DETERMINE, PETSC_DETERMINE,
                       this, &shell_),
        "MatCreateShell");
  check(MatShellSetOperation(shell_, MATOP_MULT, reinterpret_cast<void (*)(void)>(&PetscPatchOperator::multiply)),
        "MatShellSetOperation");
  check(MatSetOption(shell_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
}

PetscPatchOperator::~PetscPatchOperator() {
  if (!PetscInitializeCalled || PetscFinalizeCalled) return;  // PETSc already gone with the process's session
  for (Mat* m : {&shell_, &gradients_}) MatDestroy(m);
  for (Vec* v : {&curvature_, &node_values_, &shift_, &shifted_}) VecDestroy(v);
}

PetscInt PetscPatchOperator::owned_row_node(PetscInt local) const {
  return numbering_.node_order[static_cast<size_t>((numbering_.first_row + local) / 3)];
}

// Row (b, i) of G holds, for every node a of b's patch, g_a's component i at b; a prescribed dof's row is empty (K's
// row there is A's identity row).
void PetscPatchOperator::update() {
  const std::vector<int>& pointers = nodal_.patch_pointers();
  const std::vector<int>& patch = nodal_.patch_nodes();
  std::vector<PetscInt> columns;
  std::vector<PetscScalar> values;
  for (PetscInt l = 0; l < numbering_.owned_rows; ++l) {
    const PetscInt b = owned_row_node(l), row = numbering_.first_row + l;
    const int component = static_cast<int>(row % 3);
    const bool free = free_index_[3 * static_cast<size_t>(b) + static_cast<size_t>(component)] >= 0;
    columns.clear();
    values.clear();
    for (int k = pointers[static_cast<size_t>(b)]; k < pointers[static_cast<size_t>(b) + 1]; ++k) {
      columns.push_back(position_of_node_[static_cast<size_t>(patch[static_cast<size_t>(k)])]);
      values.push_back(free ? nodal_.gradient_at_patch_entry(static_cast<size_t>(k))[component] : 0.0);
    }
    check(MatSetValues(gradients_, 1, &row, static_cast<PetscInt>(columns.size()), columns.data(), values.data(),
                       INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(gradients_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(gradients_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  PetscScalar* d = nullptr;
  check(VecGetArray(curvature_, &d), "VecGetArray");
  for (PetscInt p = 0; p < numbering_.owned_rows / 3; ++p)
    d[p] = nodal_.node_curvature(static_cast<size_t>(numbering_.node_order[static_cast<size_t>(numbering_.first_row / 3 + p)]));
  check(VecRestoreArray(curvature_, &d), "VecRestoreArray");
  shifted_solve_ = false;
}

// diag(G D G^T) at row (b, i): Σ over the nodes a of b's patch of D_a (g_a's component i at b)^2; every rank has
// D for every node.
void PetscPatchOperator::add_patch_diagonal(Vec diagonal) const {
  const std::vector<int>& pointers = nodal_.patch_pointers();
  const std::vector<int>& patch = nodal_.patch_nodes();
  PetscScalar* d = nullptr;
  check(VecGetArray(diagonal, &d), "VecGetArray");
  for (PetscInt l = 0; l < numbering_.owned_rows; ++l) {
    const PetscInt b = owned_row_node(l);
    const int component = static_cast<int>((numbering_.first_row + l) % 3);
    if (free_index_[3 * static_cast<size_t>(b) + static_cast<size_t>(component)] < 0) continue;
    for (int k = pointers[static_cast<size_t>(b)]; k < pointers[static_cast<size_t>(b) + 1]; ++k) {
      const double g = nodal_.gradient_at_patch_entry(static_cast<size_t>(k))[component];
      d[l] += nodal_.node_curvature(static_cast<size_t>(patch[static_cast<size_t>(k)])) * g * g;
    }
  }
  check(VecRestoreArray(diagonal, &d), "VecRestoreArray");
}

void PetscPatchOperator::diagonal(Vec diagonal) const {
  check(MatGetDiagonal(element_part_, diagonal), "MatGetDiagonal");
  add_patch_diagonal(diagonal);
}

void PetscPatchOperator::set_shift(double fraction) {
  shifted_solve_ = fraction != 0;
  if (!shifted_solve_) return;
  diagonal(shift_);
  check(VecScale(shift_, fraction), "VecScale");
}

PetscErrorCode PetscPatchOperator::multiply(Mat shell, Vec x, Vec y) {
  PetscFunctionBeginUser;
  PetscPatchOperator* self = nullptr;
  PetscCall(MatShellGetContext(shell, &self));
  PetscCall(MatMult(self->element_part_, x, y));
  PetscCall(MatMultTranspose(self->gradients_, x, self->node_values_));
  PetscCall(VecPointwiseMult(self->node_values_, self->node_values_, self->curvature_));
  PetscCall(MatMultAdd(self->gradients_, self->node_values_, y, y));
  if (self->shifted_solve_) {
    PetscCall(VecPointwiseMult(self->shifted_, self->shift_, x));
    PetscCall(VecAXPY(y, 1.0, self->shifted_));
  }
  PetscFunctionReturn(0);
}

}  // namespace needlekit::fem::detail
