// Internal: the averaged nodal volume tetrahedron (Bonet & Burton 1998, "A simple average nodal pressure tetrahedral
// element for incompressible and nearly incompressible dynamic explicit applications", Commun Numer Meth Eng 14,
// 437-449; the nodal-averaged J of FEBio's UT4) for linear tetrahedra, as a potential for implicit Newton.
//
// The neo-Hookean energy is split into the element part W_e = μ/2 (I1 - 3) - μ ln J + λ_s/2 (ln J)^2, evaluated per
// element as usual, and the rest of the volumetric part, U(J) = (λ - λ_s)/2 (ln J)^2 — the term whose large modulus
// locks linear tetrahedra as ν → 1/2 — evaluated at the nodes on the nodal volume ratio
//     J̄_a = v_a / V_a,   v_a = Σ_{e∋a} J_e V_e / 4,   V_a = Σ_{e∋a} V_e / 4        (Bonet & Burton, Eqs 8-10)
// with λ_a = Σ_{e∋a} (λ_e - λ_s,e) V_e / 4 / V_a. Total energy Π = Σ_e V_e W_e(F_e) + Σ_a V_a U_a(J̄_a). One volume
// constraint per node instead of per element removes the locking (about one constraint per unknown for tets instead
// of five or six). A homogeneous deformation gives J̄_a = J_e = J everywhere: the standard law exactly.
// Stabilisation: λ_s = min(λ, β μ) with β = SolverOptions::volumetric_stabilization. With λ_s = 0 the element
// volumes are free wherever their patch averages are kept (the nodal average's spurious volumetric modes): deep
// under a flat punch at ν = 0.49 single elements then collapse and invert. The element's own share λ_s resists that
// like a material of ν = β / (2 (β + 1)) (0.25 at the default β = 1), which linear tetrahedra carry without
// locking. This is the volumetric counterpart of the α-blend of the standard element into FEBio's UT4 (Gee,
// Dohrmann, Key & Wall 2009, "A uniform nodal strain tetrahedron with isochoric stabilization", Int J Numer Meth
// Eng 78, 429-443), with the element's share tied to μ rather than to λ so that it does not lock as ν → 1/2.
//
// With h_b = F_e^-T ∇N_b (so ∂J_e/∂u_b = J_e h_b) and g_a = ∂v_a/∂u = Σ_{e∋a} V_e/4 J_e h_e:
//     force   f = Σ_e V_e p̄_e J_e h_e + element part,   p̄_e = (1/4) Σ_{a∈e} U_a'(J̄_a)
//     tangent K = Σ_e V_e p̄_e J_e (h_b h_c^T - h_c h_b^T) + Σ_a U_a''(J̄_a) / V_a g_a g_a^T + element part.
// The last term couples every pair of nodes of a node's patch: the tangent's pattern is the mesh's two-ring.
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <vector>

#include "function_space.hpp"
#include "sparse_pattern.hpp"

namespace needlekit::fem::detail {

class NodalVolumeAverage {
public:
  // `treated`: per element, 1 when its volumetric term is averaged at the nodes (linear tetrahedra only).
  // `stabilization`: β >= 0 above. Sets the treated elements' λ in space.lame to λ_s = min(λ, β μ) and keeps λ - λ_s
  // for the nodes.
  NodalVolumeAverage(FunctionSpace& space, const std::vector<char>& treated, double stabilization);
  int element_count() const { return element_count_; }
  bool treated(int element) const { return treated_[static_cast<size_t>(element)] != 0; }

  // From the displacement u: J_e, J_e h_e of the treated elements, J̄_a, the pressures and (with_tangent) g_a.
  // The volumetric energy into `energy`. False when some J_e or J̄_a <= 0 (inverted); inverted_element() then names
  // the lowest-numbered element with J_e <= 0 (or, when only a nodal J̄_a is, the first element of that node).
  bool update(const Eigen::VectorXd& u, bool with_tangent, double& energy, tbb::task_arena& arena);
  int inverted_element() const { return inverted_element_; }
  // p̄_e (Pa) and J_e h_e of a treated element at the last update.
  double element_pressure(int element) const { return element_pressure_[static_cast<size_t>(element)]; }
  double element_volume_ratio(int element) const { return element_j_[static_cast<size_t>(element)]; }
  const Eigen::Matrix<double, 3, 4>& element_jh(int element) const { return element_jh_[static_cast<size_t>(element)]; }

  // c_e = (1/4) Σ_{a∈e} max(U_a''(J̄_a), 0) (Pa) at the last update: the split preconditioner's element bulk term
  // c_e V_e (J_e h_e)(J_e h_e)^T bounds the patch term from above, as g_a g_a^T / V_a <= Σ_{e∋a} V_e/4 (J_e h_e)(J_e h_e)^T
  // (Cauchy-Schwarz on the weights V_e/4), and it couples the element's own nodes only.
  double element_bulk_curvature(int element) const;

  // Adds Σ_a U_a''/V_a g_a g_a^T into the upper-triangle `values` (columns in parallel, each written by one task:
  // deterministic whatever the number of threads).
  void add_patch_tangent(const std::vector<int>& free_index, const UpperPattern& pattern, std::vector<double>& values,
                         tbb::task_arena& arena) const;
  // The linear predictor's coupling of the patch term to the prescribed dofs: kdup += K_fp dup.
  void add_prescribed_coupling(const std::vector<int>& free_index, const Eigen::VectorXd& dup,
                               Eigen::VectorXd& kdup) const;

  // The patch term as the product G D G^T of the nodal volume gradients G = [g_a] (free dofs x nodes) and
  // D = diag(max(U_a'', 0) / V_a), for the two-grid preconditioner of the nodal-averaged tangent
  // (nodal_volume_preconditioner.hpp). `x`, `y`: free-dof vectors (free_index numbering); `q`: one value per node.
  // q = G^T x (the nodal volume changes), and y += G q: each output entry written by one task (deterministic).
  void gradient_transpose_product(const std::vector<int>& free_index, const Eigen::VectorXd& x, Eigen::VectorXd& q,
                                  tbb::task_arena& arena) const;
  void add_gradient_product(const std::vector<int>& free_index, const Eigen::VectorXd& q, Eigen::VectorXd& y,
                            tbb::task_arena& arena) const;
  // D_a = U_a''(J̄_a) / V_a (Pa/m^3) at the last update.
  double node_curvature(size_t node) const { return node_curvature_[node]; }
  // The patch term into a dense matrix whose row and column of free dof f is position[f] (QuasiStaticSolver::
  // linearization when K does not store it).
  void add_patch_tangent(const std::vector<int>& free_index, const std::vector<Eigen::Index>& position,
                         Eigen::MatrixXd& dense) const;
  // Per node, 1 / (1 / D_a + C_a) with C_a = Σ_{e∋a} V_e / (4 κ_e), κ_e = λ_s + 2μ/3 (Pa/m^3; 0 where D_a = 0):
  // the inverse of a diagonal Schur complement S = D^-1 + G^T A^-1 G that bounds it from above when A holds the
  // element part (μ and λ_s): with δv = G^T v the nodal volume changes and δJ_e the element's,
  // (q^T G^T v)^2 = (Σ_e V_e q̄_e δJ_e)^2 <= Σ_e κ_e V_e δJ_e^2 · Σ_e V_e q̄_e^2 / κ_e (Cauchy-Schwarz), the first
  // factor <= v^T A v ((tr ε)^2 <= 3 ε:ε puts 2μ/3 (tr ε)^2 under the deviatoric energy), the second
  // <= Σ_a q_a^2 C_a (q̄_e^2 <= the mean of q_a^2).
  double inverse_schur_diagonal(size_t node) const;

  // Node patches as groups for the sparse pattern: patch_pointers (nodes + 1) into patch_nodes (sorted).
  const std::vector<int>& patch_pointers() const { return patch_pointers_; }
  const std::vector<int>& patch_nodes() const { return patch_nodes_; }
  // For the entry k of node b's patch (k in [patch_pointers()[b], patch_pointers()[b + 1]), a = patch_nodes()[k]):
  // g_a's part at node b (m^3) at the last update with tangent, that is G's three rows of node b in node a's column.
  const Eigen::Vector3d& gradient_at_patch_entry(size_t k) const {
    return patch_gradient_[static_cast<size_t>(patch_transpose_[k])];
  }

private:
  const FunctionSpace& space_;
  std::vector<char> treated_;
  double stabilization_;  // β: the element keeps λ_s = min(λ, β μ)
  int element_count_ = 0;
  std::vector<int> node_element_pointers_, node_elements_;  // node -> treated elements containing it
  std::vector<int> patch_pointers_, patch_nodes_;           // node -> nodes of its patch (itself included)
  std::vector<double> node_volume_, node_lambda_;           // V_a (m^3), λ_a (Pa)
  std::vector<double> node_compliance_;                     // C_a = Σ_{e∋a} V_e / (4 κ_e), m^3/Pa
  std::vector<int> patch_transpose_;                        // per patch entry (a, b): the entry (b, a) of b's patch
  std::vector<double> element_j_, element_pressure_;
  std::vector<Eigen::Matrix<double, 3, 4>> element_jh_;
  std::vector<double> node_curvature_;                      // U_a''(J̄_a) / V_a, Pa/m^3
  int inverted_element_ = -1;
  double element_lambda(const LameConstants& lame) const;  // λ_s (Pa)
  // J̄_a = Σ_e J_e V_e/4 / V_a over the treated elements of node n (node_volume_[n] > 0).
  double node_volume_ratio(size_t n) const;
  std::vector<Eigen::Vector3d> patch_gradient_;             // g_a restricted to each patch node, aligned with
                                                            // patch_nodes_
};

}  // namespace needlekit::fem::detail
