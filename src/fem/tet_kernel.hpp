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
template <int N>
bool tet_kernel(const Grad<N>* gradients, const double* weights, int points, MaterialLaw law, const LameConstants& lame,
                const Eigen::Matrix<double, 3, N>& u, double& energy, Eigen::Matrix<double, 3, N>& force,
                Eigen::Matrix<double, 3 * N, 3 * N>* tangent) {
  energy = 0;
  force.setZero();
  if (tangent) tangent->setZero();
  bool valid = true;
  for (int q = 0; q < points; ++q) {
    const Grad<N>& g = gradients[q];
    const double w = weights[q];
    const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + u * g.transpose();  // F_iJ = δ_iJ + u_ia N_a,J
    const StressResponse r = stress_response(law, lame, f, tangent != nullptr);
    if (!r.valid) valid = false;  // inverted: the caller rejects the state
    if (!std::isfinite(r.energy_density)) continue;
    const Eigen::Matrix3d& s = r.second_piola_kirchhoff;
    energy += w * r.energy_density;
    force.noalias() += w * (f * s) * g;  // Eq 3.8: f_a = ∫ F S ∇N_a dV  (= K u + g(u) u)
    if (!tangent) continue;
    Eigen::Matrix<double, 6, 3 * N> b;  // δE (Voigt, engineering shear) = B δu: the nonlinear B of Eq 3.3
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < 3; ++i) {
        const int c = 3 * a + i;
        b(0, c) = f(i, 0) * g(0, a);
        b(1, c) = f(i, 1) * g(1, a);
        b(2, c) = f(i, 2) * g(2, a);
        b(3, c) = f(i, 0) * g(1, a) + f(i, 1) * g(0, a);
        b(4, c) = f(i, 1) * g(2, a) + f(i, 2) * g(1, a);
        b(5, c) = f(i, 2) * g(0, a) + f(i, 0) * g(2, a);
      }
    // Coefficient-based (lazy) products: at these fixed sizes Eigen's blocked GEMM path spends more time packing than
    // multiplying (measured 478 -> 357 ns per linear tetrahedron, 1603 -> 1103 ns per T10 quadrature point).
    const Eigen::Matrix<double, 6, 3 * N> cb = (w * r.tangent).lazyProduct(b);
    tangent->noalias() += b.transpose().lazyProduct(cb);  // material part (Eq 3.6 with the current B)
    const Eigen::Matrix<double, N, N> h = g.transpose() * s * g;  // geometric (initial-stress) part
    for (int a = 0; a < N; ++a)
      for (int bb = 0; bb < N; ++bb) {
        const double v = w * h(a, bb);
        for (int i = 0; i < 3; ++i) (*tangent)(3 * a + i, 3 * bb + i) += v;
      }
  }
  return valid;
}

}  // namespace needlekit::fem::detail
