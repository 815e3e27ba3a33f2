#include "needlekit/fem/hyperelastic_law.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace needlekit::fem {

LameConstants lame_constants(double youngs_modulus, double poisson_ratio) {
  // Eqs 3.4/3.5 with the notes' prefactor E/((1+ν)(1-2ν)): diagonal (1-ν)·pre = λ + 2μ, off-diagonal ν·pre = λ,
  // shear (0.5-ν)·pre = μ.
  const double nu = poisson_ratio;
  return {youngs_modulus * nu / ((1 + nu) * (1 - 2 * nu)), youngs_modulus / (2 * (1 + nu))};
}

Eigen::Matrix3d green_lagrange_strain(const Eigen::Matrix3d& f) {
  // Eq 3.3 (corrected): E_ij = (u_i,j + u_j,i + u_k,i u_k,j) / 2 = (F^T F - I) / 2.
  return 0.5 * (f.transpose() * f - Eigen::Matrix3d::Identity());
}

StressResponse stress_response(MaterialLaw law, const LameConstants& lame, const Eigen::Matrix3d& f,
                               bool with_tangent) {
  StressResponse r;
  const double lambda = lame.lambda, mu = lame.mu;
  if (law == MaterialLaw::StVenantKirchhoff) {
    // S = D E (Eqs 3.4, 3.5): S = λ tr(E) I + 2μ E; W = λ/2 tr(E)^2 + μ E:E.
    // SVK's energy stays finite for inverted elements (J <= 0), where its solutions are spurious (the law "fails
    // under large compression"): flag them so that the solver rejects the state.
    r.valid = f.determinant() > 0;
    const Eigen::Matrix3d e = green_lagrange_strain(f);
    const double tr = e.trace();
    r.second_piola_kirchhoff = lambda * tr * Eigen::Matrix3d::Identity() + 2 * mu * e;
    r.energy_density = 0.5 * lambda * tr * tr + mu * e.squaredNorm();
    if (with_tangent) {  // dS/dE = λ I⊗I + 2μ 𝕀
      r.tangent_lambda = lambda;
      r.tangent_mu = mu;
      r.tangent_metric.setIdentity();
    }
    return r;
  }
  // Compressible neo-Hookean: W = μ/2 (I1 - 3) - μ ln J + λ/2 (ln J)^2, S = μ(I - C^-1) + λ ln J C^-1,
  // dS/dE = λ C^-1 ⊗ C^-1 + 2(μ - λ ln J) C^-1 ⊙ C^-1.
  const double j = f.determinant();
  if (!(j > 0)) {
    r.valid = false;
    r.energy_density = std::numeric_limits<double>::infinity();
    r.second_piola_kirchhoff.setZero();
    return r;
  }
  const Eigen::Matrix3d c = f.transpose() * f;
  const Eigen::Matrix3d ci = c.inverse();
  const double lnj = std::log(j);
  r.second_piola_kirchhoff = mu * (Eigen::Matrix3d::Identity() - ci) + lambda * lnj * ci;
  r.energy_density = 0.5 * mu * (c.trace() - 3) - mu * lnj + 0.5 * lambda * lnj * lnj;
  if (with_tangent) {
    r.tangent_lambda = lambda;
    r.tangent_mu = mu - lambda * lnj;
    r.tangent_metric = ci;
  }
  return r;
}

Eigen::Matrix3d cauchy_stress(const Eigen::Matrix3d& f, const Eigen::Matrix3d& s) {
  return f * s * f.transpose() / f.determinant();
}

double von_mises_stress(const Eigen::Matrix3d& t) {
  const Eigen::Matrix3d dev = t - t.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * dev.squaredNorm());
}

}  // namespace needlekit::fem
