// Element-level verification of the total-Lagrangian tetrahedra (dissertation §3.4): consistent tangent vs central
// finite differences of the internal force, internal force vs finite differences of the energy, and the laws'
// closed forms.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "needlekit/fem/tet_element.hpp"

using namespace needlekit::fem;

namespace {

std::vector<Eigen::Vector3d> element_nodes(int n, double scale, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto& p : x) p = scale * (p + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng)));
  if (n == 10) {
    const int e[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (auto& ed : e) x.push_back(0.5 * (x[ed[0]] + x[ed[1]]));
  }
  return x;
}

struct Case {
  MaterialLaw law;
  int nodes;
  double scale;  // m
};

class ElementTangent : public ::testing::TestWithParam<Case> {};

TEST_P(ElementTangent, MatchesCentralFiniteDifferences) {
  const Case c = GetParam();
  std::mt19937 rng(42);
  const auto x = element_nodes(c.nodes, c.scale, rng);
  const auto geo = element_geometry(x);
  ASSERT_GT(geo.volume, 0);
  const LameConstants lame = lame_constants(0.2e6, 0.45);
  std::uniform_real_distribution<double> du(-0.08, 0.08);  // finite strains of several percent
  Eigen::VectorXd u(3 * c.nodes);
  for (int i = 0; i < u.size(); ++i) u[i] = c.scale * du(rng);
  const auto r = element_response(geo, c.law, lame, u, true);
  ASSERT_TRUE(r.valid);
  // The tangent is symmetric (hyperelastic potential).
  EXPECT_LT((r.tangent - r.tangent.transpose()).norm(), 1e-12 * r.tangent.norm());
  const double h = 1e-6 * c.scale;
  Eigen::MatrixXd kfd(3 * c.nodes, 3 * c.nodes);
  Eigen::VectorXd ffd(3 * c.nodes);
  for (int j = 0; j < u.size(); ++j) {
    Eigen::VectorXd up = u, um = u;
    up[j] += h;
    um[j] -= h;
    const auto rp = element_response(geo, c.law, lame, up, false), rm = element_response(geo, c.law, lame, um, false);
    kfd.col(j) = (rp.force - rm.force) / (2 * h);
    ffd[j] = (rp.energy - rm.energy) / (2 * h);
  }
  EXPECT_LT((kfd - r.tangent).norm() / r.tangent.norm(), 1e-6) << to_string(c.law) << " " << c.nodes;
  EXPECT_LT((ffd - r.force).norm() / r.force.norm(), 1e-6);
  // Rigid translation gives no force.
  Eigen::VectorXd t(3 * c.nodes);
  for (int a = 0; a < c.nodes; ++a) t.segment<3>(3 * a) = c.scale * Eigen::Vector3d(0.3, -0.2, 0.1);
  const auto rt = element_response(geo, c.law, lame, t, false);
  EXPECT_LT(rt.force.norm(), 1e-9 * r.force.norm());
}

INSTANTIATE_TEST_SUITE_P(LawsOrdersScales, ElementTangent,
                         ::testing::Values(Case{MaterialLaw::StVenantKirchhoff, 4, 1e-4},
                                           Case{MaterialLaw::NeoHookean, 4, 1e-4},
                                           Case{MaterialLaw::StVenantKirchhoff, 10, 1e-4},
                                           Case{MaterialLaw::NeoHookean, 10, 1e-4},
                                           Case{MaterialLaw::StVenantKirchhoff, 10, 1.0},
                                           Case{MaterialLaw::NeoHookean, 4, 1.0}));

TEST(ElementRotation, RigidRotationIsStressFreeForBothLaws) {
  std::mt19937 rng(7);
  const auto x = element_nodes(10, 1e-4, rng);
  const auto geo = element_geometry(x);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::VectorXd u(30);
  for (int a = 0; a < 10; ++a) u.segment<3>(3 * a) = rot * x[a] - x[a];
  for (auto law : {MaterialLaw::StVenantKirchhoff, MaterialLaw::NeoHookean}) {
    const auto r = element_response(geo, law, lame_constants(1e6, 0.4), u, false);
    EXPECT_LT(r.force.norm(), 1e-9 * 1e6 * 1e-8) << to_string(law);
    EXPECT_NEAR(r.energy, 0, 1e-20);
  }
}

TEST(HyperelasticLaw, SvkUniaxialStressClosedForm) {
  // SVK under uniaxial stress: E22 = E33 = -nu E11 and S11 = E * E11 exactly (Eqs 3.4/3.5 with the notes' prefactor).
  const double e = 0.2e6, nu = 0.3;
  const auto lame = lame_constants(e, nu);
  for (double stretch : {0.7, 0.95, 1.1, 1.5}) {
    const double e11 = 0.5 * (stretch * stretch - 1);
    const double lateral = std::sqrt(1 - 2 * nu * e11);
    const Eigen::Matrix3d f = Eigen::Vector3d(stretch, lateral, lateral).asDiagonal();
    const auto r = stress_response(MaterialLaw::StVenantKirchhoff, lame, f);
    EXPECT_NEAR(r.second_piola_kirchhoff(0, 0), e * e11, 1e-9 * e);
    EXPECT_NEAR(r.second_piola_kirchhoff(1, 1), 0, 1e-9 * e);
    EXPECT_NEAR(r.energy_density, 0.5 * e * e11 * e11, 1e-9 * e);
  }
}

TEST(HyperelasticLaw, NeoHookeanSimpleShearClosedForm) {
  // Simple shear F = I + g e1 (x) e2 (J = 1): sigma_12 = mu g, sigma_11 - sigma_22 = mu g^2.
  const auto lame = lame_constants(0.3e6, 0.45);
  for (double g : {0.01, 0.3, 1.0}) {
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    f(0, 1) = g;
    const auto r = stress_response(MaterialLaw::NeoHookean, lame, f);
    const Eigen::Matrix3d s = cauchy_stress(f, r.second_piola_kirchhoff);
    EXPECT_NEAR(s(0, 1), lame.mu * g, 1e-9 * lame.mu);
    EXPECT_NEAR(s(0, 0) - s(1, 1), lame.mu * g * g, 1e-9 * lame.mu);
  }
}

TEST(HyperelasticLaw, LawsAgreeAtSmallStrain) {
  const auto lame = lame_constants(1e6, 0.45);
  Eigen::Matrix3d grad;
  grad << 1, 2, -1, 0.5, -2, 1, 0.3, 0.2, 1.5;
  const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + 1e-6 * grad;
  const auto a = stress_response(MaterialLaw::StVenantKirchhoff, lame, f);
  const auto b = stress_response(MaterialLaw::NeoHookean, lame, f);
  EXPECT_LT((a.second_piola_kirchhoff - b.second_piola_kirchhoff).norm(), 1e-4 * a.second_piola_kirchhoff.norm());
  EXPECT_NEAR(a.tangent_lambda, b.tangent_lambda, 1e-4 * a.tangent_lambda);
  EXPECT_NEAR(a.tangent_mu, b.tangent_mu, 1e-4 * a.tangent_mu);
  EXPECT_LT((a.tangent_metric - b.tangent_metric).norm(), 1e-4);
}

}  // namespace
