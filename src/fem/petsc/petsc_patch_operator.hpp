// Internal: the PETSc backend's operator for the tangent of the nodal-averaged tetrahedron, K = A + G D G^T
// (nodal_volume.hpp), with the patch term G D G^T applied in the product, as the built-in two-grid solve does
// (TangentLayout::patch_term_in_product), instead of assembled.
//
// A is the assembled one-ring element part (a MatMPIAIJ of PetscLinearSolve), G the nodal volume gradients as a
// MatMPIAIJ of the dof rows by the nodes, D = diag(U_a'' / V_a) a Vec over the nodes. Rows and nodes are
// distributed alike (a node's three dofs and the node on the same rank), and every rank holds the nodal average of
// the whole mesh, so each rank fills its own rows of G and entries of D with no communication. A MATSHELL applies
//     y = A x + G (D ∘ (G^T x)) + s ∘ x
// (s: the shifted solves' diagonal shift, usually none). Why not assemble K: its pattern is the mesh's two-ring, about
// four times A's entries (a row couples a node to the patches of its patch); assembling it was the backend's largest
// cost after the solve, GAMG's set-up (the Galerkin products) grows with it, and every rank computed the whole patch
// term (BENCHMARKS.md, "The 10 × 10 array at ≥ 1 M tetrahedra"). G has one entry per node of a node's patch per dof.
#pragma once
#include <petscmat.h>

#include <span>
#include <vector>

#include "../nodal_volume.hpp"

namespace needlekit::fem::detail {

class PetscPatchOperator {
public:
  // How PetscLinearSolve numbers the dofs: the nodes in PETSc's order (node_order: position -> node), per dof its
  // PETSc row, and this rank's rows [first_row, first_row + owned_rows) (whole nodes). `element_part`: A, assembled
  // by the caller before each solve. All kept by reference.
  struct Numbering {
    std::span<const int> node_order;
    std::span<const PetscInt> row_of_dof;
    PetscInt first_row = 0;
    PetscInt owned_rows = 0;
  };
  PetscPatchOperator(const NodalVolumeAverage& nodal, const std::vector<int>& free_index, const Numbering& numbering,
                     Mat element_part);
  ~PetscPatchOperator();
  PetscPatchOperator(const PetscPatchOperator&) = delete;
  PetscPatchOperator& operator=(const PetscPatchOperator&) = delete;

  // G's values and D from the nodal average's last update (with its tangent).
  void update();
  // The shell K above.
  Mat operator_matrix() const { return shell_; }
  // diag(K) over this rank's rows (diag(A) + diag(G D G^T)).
  void diagonal(Vec diagonal) const;
  // s = fraction * diag(K) from now on (0: no shift).
  void set_shift(double fraction);

private:
  static PetscErrorCode multiply(Mat shell, Vec x, Vec y);
  void add_patch_diagonal(Vec diagonal) const;
  PetscInt owned_row_node(PetscInt local) const;  // the node of a local row

  const NodalVolumeAverage& nodal_;
  const std::vector<int>& free_index_;
  Numbering numbering_;
  Mat element_part_;
  std::vector<PetscInt> position_of_node_;  // node -> its position in node_order (G's column)
  Mat gradients_ = nullptr, shell_ = nullptr;
  Vec curvature_ = nullptr, node_values_ = nullptr, shift_ = nullptr, shifted_ = nullptr;
  bool shifted_solve_ = false;
};

}  // namespace needlekit::fem::detail
