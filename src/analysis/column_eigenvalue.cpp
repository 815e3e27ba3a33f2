#include "needlekit/analysis/column_eigenvalue.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {
namespace {

// Fixed-free column, EI(s)·u'' + P·u = 0, u(0) = 0 at the tip, u'(L) = 0 at the clamped base. With nodes
// s_i = i·h (i = 1..n) the central difference gives the symmetric pencil K u = P W u:
//   K = tridiag(−1, 2, −1)/h² with the last row halved (ghost node u_{n+1} = u_{n−1}), W = diag(1/EI(s_i)) with
//   the last entry halved. The lowest eigenvalue is found by inverse iteration (Thomas algorithm) with the Rayleigh
// quotient; it converges at the rate λ1/λ2 (1/9 for a uniform column).
double fixed_free_load(const std::function<double(double)>& flexural_rigidity, double length, int n) {
  const double h = length / n;
  std::vector<double> w(n), u(n, 1.0), rhs(n), c(n);
  for (int i = 0; i < n; ++i) {
    const double ei = flexural_rigidity((i + 1) * h);
    if (!(ei > 0) || !std::isfinite(ei)) {
      throw InvalidInput(fmt::format("column: flexural rigidity {} N·m² at s = {} m must be positive", ei, (i + 1) * h));
    }
    w[i] = (i == n - 1 ? 0.5 : 1.0) / ei;
  }
  const double off = -1.0 / (h * h);
  auto diag = [&](int i) { return (i == n - 1 ? 1.0 : 2.0) / (h * h); };
  auto apply_k = [&](const std::vector<double>& x, int i) {
    double y = diag(i) * x[i];
    if (i > 0) y += off * x[i - 1];
    if (i < n - 1) y += off * x[i + 1];
    return y;
  };
  double lambda = 0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    // Solve K x = W u (Thomas algorithm; K is SPD and diagonally dominant).
    for (int i = 0; i < n; ++i) rhs[i] = w[i] * u[i];
    c[0] = off / diag(0);
    rhs[0] /= diag(0);
    for (int i = 1; i < n; ++i) {
      const double m = diag(i) - off * c[i - 1];
      c[i] = off / m;
      rhs[i] = (rhs[i] - off * rhs[i - 1]) / m;
    }
    for (int i = n - 2; i >= 0; --i) rhs[i] -= c[i] * rhs[i + 1];
    double num = 0, den = 0, norm = 0;
    for (int i = 0; i < n; ++i) {
      num += rhs[i] * apply_k(rhs, i);
      den += rhs[i] * w[i] * rhs[i];
      norm = std::max(norm, std::abs(rhs[i]));
    }
    const double next = num / den;  // Rayleigh quotient
    for (int i = 0; i < n; ++i) u[i] = rhs[i] / norm;
    if (iteration > 0 && std::abs(next - lambda) <= 1e-14 * next) return next;
    lambda = next;
  }
  return lambda;
}

// Pinned or clamped tip: (EI w'')'' + P w'' = 0 with Hermite-cubic Euler–Bernoulli elements (EI by 3-point Gauss
// per element) and the consistent geometric stiffness; the dense pencil is solved as K_g φ = μ K φ, P = 1/μ_max.
double hermite_beam_load(const std::function<double(double)>& flexural_rigidity, double length, EndCondition end,
                         int elements) {
  const int dofs = 2 * (elements + 1);  // (w, w') per node; node 0 is the tip (s = 0), node n the base
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(dofs, dofs), g = Eigen::MatrixXd::Zero(dofs, dofs);
  const double h = length / elements;
  const double gauss_x[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, gauss_w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (int e = 0; e < elements; ++e) {
    Eigen::Matrix4d ke = Eigen::Matrix4d::Zero();
    for (int q = 0; q < 3; ++q) {
      const double xi = 0.5 * (gauss_x[q] + 1);  // in [0, 1]
      const double ei = flexural_rigidity((e + xi) * h);
      if (!(ei > 0) || !std::isfinite(ei)) throw InvalidInput("column: flexural rigidity must be positive");
      // Second derivatives of the Hermite shape functions with respect to s.
      Eigen::Vector4d b((12 * xi - 6) / (h * h), (6 * xi - 4) / h, (6 - 12 * xi) / (h * h), (6 * xi - 2) / h);
      ke += 0.5 * gauss_w[q] * h * ei * b * b.transpose();
    }
    Eigen::Matrix4d ge;
    ge << 36, 3 * h, -36, 3 * h, 3 * h, 4 * h * h, -3 * h, -h * h, -36, -3 * h, 36, -3 * h, 3 * h, -h * h, -3 * h,
        4 * h * h;
    ge /= 30 * h;
    k.block<4, 4>(2 * e, 2 * e) += ke;
    g.block<4, 4>(2 * e, 2 * e) += ge;
  }
  // Boundary conditions: base clamped (w = w' = 0); tip pinned (w = 0) or clamped (w = w' = 0).
  std::vector<int> keep;
  for (int d = 0; d < dofs; ++d) {
    const bool base = d >= dofs - 2;
    const bool tip_w = d == 0, tip_slope = d == 1;
    if (base || tip_w || (tip_slope && end == EndCondition::FixedFixed)) continue;
    keep.push_back(d);
  }
  const int m = static_cast<int>(keep.size());
  Eigen::MatrixXd kr(m, m), gr(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      kr(i, j) = k(keep[i], keep[j]);
      gr(i, j) = g(keep[i], keep[j]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(gr, kr, Eigen::EigenvaluesOnly);
  return 1.0 / solver.eigenvalues().maxCoeff();
}

}  // namespace

double column_buckling_load(const std::function<double(double)>& flexural_rigidity, double length,
                            const ColumnEigenvalueOptions& options) {
  if (!(length > 0) || !std::isfinite(length)) throw InvalidInput("column: length must be positive");
  if (options.intervals < 4) throw InvalidInput("column: intervals must be >= 4");
  if (options.end_condition == EndCondition::FixedFree) {
    const double coarse = fixed_free_load(flexural_rigidity, length, options.intervals);
    const double fine = fixed_free_load(flexural_rigidity, length, 2 * options.intervals);
    return (4 * fine - coarse) / 3;  // Richardson extrapolation of the O(h²) scheme
  }
  return hermite_beam_load(flexural_rigidity, length, options.end_condition, std::max(options.intervals / 4, 40));
}

}  // namespace needlekit::analysis
