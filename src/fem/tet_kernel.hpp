// Internal: fixed-size total-Lagrangian tetrahedron kernel shared by tet_element.cpp and the solver.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cmath>

#include "needlekit/fem/hyperelastic_law.hpp"

namespace needlekit::fem::detail {

// Quadrature of the reference tetrahedron (volume 1/6) in barycentric coordinates (L0..L3).
struct TetQuadrature {
  int points;
  std::array<std::array<double, 4>, 4> barycentric;
  std::array<double, 4> weights;  // sum 1/6
};
inline TetQuadrature tet_quadrature(int nodes) {
  if (nodes == 4) return {1, {{{0.25, 0.25, 0.25, 0.25}}}, {{1.0 / 6.0}}};
  const double a = 0.5854101966249685, b = 0.1381966011250105;  // degree-2 Gauss rule
  return {4, {{{a, b, b, b}, {b, a, b, b}, {b, b, a, b}, {b, b, b, a}}}, {{1.0 / 24, 1.0 / 24, 1.0 / 24, 1.0 / 24}}};
}

// Edges of the T10 in VTK order: mid-node 4 + k sits on edge k.
inline constexpr int tet_edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// dN/dL (barycentric derivatives) for 4 or 10 nodes at barycentric point l: rows L0..L3, columns nodes.
inline Eigen::Matrix<double, 4, Eigen::Dynamic> shape_barycentric_gradients(int nodes, const std::array<double, 4>& l) {
  Eigen::Matrix<double, 4, Eigen::Dynamic> d = Eigen::Matrix<double, 4, Eigen::Dynamic>::Zero(4, nodes);
  if (nodes == 4) {
    for (int i = 0; i < 4; ++i) d(i, i) = 1;
    return d;
  }
  for (int i = 0; i < 4; ++i) d(i, i) = 4 * l[i] - 1;  // N_i = L_i (2 L_i - 1)
  for (int k = 0; k < 6; ++k) {                        // N = 4 L_i L_j
    const int i = tet_edges[k][0], j = tet_edges[k][1];
    d(i, 4 + k) = 4 * l[j];
    d(j, 4 + k) = 4 * l[i];
  }
  return d;
}

template <int N>
using Grad = Eigen::Matrix<double, 3, N>;

// Energy, internal force (3 x N, column per node) and tangent (3N x 3N, dof 3a+i) at displacement u (3 x N).
// `initial_gradient`: F at u = 0 (FunctionSpace::initial_gradient; I for every element but a rezoned one's).
template <int N>
bool tet_kernel(const Grad<N>* gradients, const double* weights, int points, MaterialLaw law, const LameConstants& lame,
                const Eigen::Matrix<double, 3, N>& u, double& energy, Eigen::Matrix<double, 3, N>& force,
                Eigen::Matrix<double, 3 * N, 3 * N>* tangent,
                const Eigen::Matrix3d& initial_gradient = Eigen::Matrix3d::Identity()) {
  energy = 0;
  force.setZero();
  if (tangent) tangent->setZero();
  bool valid = true;
  for (int q = 0; q < points; ++q) {
    const Grad<N>& g = gradients[q];
    const double w = weights[q];
    const Eigen::Matrix3d f = initial_gradient + u * g.transpose();  // F_iJ = δ_iJ + u_ia N_a,J (F_r for δ)
    const StressResponse r = stress_response(law, lame, f, tangent != nullptr);
    if (!r.valid) valid = false;  // inverted: the caller rejects the state
    if (!std::isfinite(r.energy_density)) continue;
    const Eigen::Matrix3d& s = r.second_piola_kirchhoff;
    energy += w * r.energy_density;
    force.noalias() += w * (f * s) * g;  // Eq 3.8: f_a = ∫ F S ∇N_a dV  (= K u + g(u) u)
    if (!tangent) continue;
    // Material part (Eq 3.6 with the current B) in closed form. With δE = sym(F^T ∇δu), K_ab,ij =
    // F_iI ∇N_a,J C_IJKL F_jK ∇N_b,L, and C = λ' A⊗A + μ' (A_IK A_JL + A_IL A_JK) (hyperelastic_law.hpp) gives,
    // with p_a = F A ∇N_a: K_ab = λ' p_a p_b^T + μ' (p_b p_a^T + (∇N_a · A ∇N_b) F A F^T). The geometric
    // (initial-stress) part adds (∇N_a · S ∇N_b) I. Against B^T C B through a 6 x 3N Voigt B: 1.8x (linear) and
    // 2.3x (quadratic) faster (BM_ElementTangent).
    const Eigen::Matrix3d fa = f * r.tangent_metric;
    const Eigen::Matrix<double, 3, N> p = fa * g;
    const Eigen::Matrix3d faf = (w * r.tangent_mu) * (fa * f.transpose());
    const Eigen::Matrix<double, N, N> metric_dots = g.transpose() * (r.tangent_metric * g);
    const Eigen::Matrix<double, N, N> stress_dots = g.transpose() * ((w * s) * g);
    const double wl = w * r.tangent_lambda, wm = w * r.tangent_mu;
    for (int a = 0; a < N; ++a)
      for (int bb = a; bb < N; ++bb) {
        const double md = metric_dots(a, bb), sd = stress_dots(a, bb);
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) {
            const double k = wl * p(i, a) * p(j, bb) + wm * p(i, bb) * p(j, a) + md * faf(i, j) + (i == j ? sd : 0.0);
            (*tangent)(3 * a + i, 3 * bb + j) += k;
            if (bb != a) (*tangent)(3 * bb + j, 3 * a + i) += k;
          }
      }
  }
  return valid;
}

}  // namespace needlekit::fem::detail
