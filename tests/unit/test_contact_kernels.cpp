// The kernels of surface contact (internal fem::detail): the first pass's signed distance to a needle with rounded
// edges and its Hessian, the second pass's plane gap of a needle point against a tissue triangle with its exact
// gradient and Hessian, the needle's sharp-feature points, and the frozen Coulomb law's force and stiffness, each
// against central finite differences at µm and m scale.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "../../src/fem/coulomb_friction.hpp"
#include "../../src/fem/needle_edge_contact.hpp"
#include "../../src/fem/rigid_surface_distance.hpp"
#include "../verification/fem_test_support.hpp"

using namespace needlekit::fem;
using namespace needlekit::fem::detail;

namespace {
class ContactKernels : public ::testing::TestWithParam<double> {};

Eigen::Matrix<double, 9, 1> stacked(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Eigen::Matrix<double, 9, 1> x;
  x << a, b, c;
  return x;
}
PlaneGap gap_at(const Eigen::Vector3d& p, const Eigen::Matrix<double, 9, 1>& x) {
  return triangle_plane_gap(p, x.segment<3>(0), x.segment<3>(3), x.segment<3>(6));
}
}  // namespace

TEST_P(ContactKernels, PlaneGapDerivativesAreExact) {
  const double s = GetParam();
  const Eigen::Vector3d p = s * Eigen::Vector3d(0.31, 0.22, -0.07);  // under the triangle: negative gap
  const auto x = stacked(s * Eigen::Vector3d(0, 0, 0.01), s * Eigen::Vector3d(1.1, 0.1, -0.05),
                         s * Eigen::Vector3d(-0.2, 0.9, 0.08));
  const PlaneGap base = gap_at(p, x);
  ASSERT_LT(base.gap, 0);
  EXPECT_NEAR(base.weights[0] + base.weights[1] + base.weights[2], 1.0, 1e-14);
  const double h = 1e-6 * s;
  double gradient_error = 0, hessian_error = 0;
  for (int k = 0; k < 9; ++k) {
    auto up = x, down = x;
    up[k] += h;
    down[k] -= h;
    const PlaneGap a = gap_at(p, up), b = gap_at(p, down);
    gradient_error = std::max(gradient_error, std::abs((a.gap - b.gap) / (2 * h) - base.gradient[k]));
    hessian_error = std::max(hessian_error, ((a.gradient - b.gradient) / (2 * h) - base.hessian.col(k)).norm() * s);
  }
  EXPECT_LT(gradient_error, 1e-8);
  EXPECT_LT(hessian_error, 1e-7);
  EXPECT_LT((base.hessian - base.hessian.transpose()).norm() * s, 1e-12);
}

TEST_P(ContactKernels, FrictionForceAndStiffnessAreTheGradientsOfItsPotential) {
  const double s = GetParam(), k = 3e3 / s;  // N/m: a stiffness that scales like E h
  FrictionState state;
  state.normal = Eigen::Vector3d(0.1, -0.2, 1).normalized();
  state.reference = s * Eigen::Vector3d(0.2, 0.1, 0.0);
  state.traction = 1e-3 * (Eigen::Vector3d(1, 0.5, 0.3) - 0.3 * state.normal).cross(state.normal);
  state.bound = 2e-3;
  // Slips of 1e-7 and 1e-5 of the scale: trial forces of about 1.3 and 30 mN against the 2 mN bound.
  for (double slip : {1e-7, 1e-5}) {
    const Eigen::Vector3d q = state.reference + slip * s * Eigen::Vector3d(0.6, -0.8, 0.05);
    const FrictionResponse base = friction_response(state, q, k);
    EXPECT_EQ(base.slipping, slip > 1e-6) << slip;
    EXPECT_LE(base.force.norm(), state.bound * (1 + 1e-12));
    EXPECT_NEAR(base.force.dot(state.normal), 0.0, 1e-15);
    const double h = 1e-9 * s;
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d up = q, down = q;
      up[i] += h;
      down[i] -= h;
      const FrictionResponse a = friction_response(state, up, k), b = friction_response(state, down, k);
      EXPECT_NEAR((a.energy - b.energy) / (2 * h), base.force[i], 1e-6 * state.bound) << slip << " " << i;
      EXPECT_LT(((a.force - b.force) / (2 * h) - base.stiffness.col(i)).norm(), 1e-5 * k) << slip << " " << i;
    }
  }
}

// The signed distance to a box rounded by r (its core's distance minus r) near a rounded edge, a rounded corner and a
// face, outside and inside the core: the normal is the distance's gradient and the Hessian the normal's derivative
// (the first pass's exact tangent k n n^T - P hess g rests on it). Nearest an edge or corner the Hessian has the
// curvature 1/r of the rounding across it; nearest a face it is zero.
TEST_P(ContactKernels, RoundedDistanceHessianIsTheNormalsDerivative) {
  const double s = GetParam(), r = 0.02 * s;
  const RigidSurfaceDistance box(test_support::box_surface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(s)),
                                 Eigen::Vector3d(0, 0, -1), r);
  struct Probe {
    Eigen::Vector3d q;
    double curvature;  // the largest eigenvalue magnitude expected, 1/m
  };
  const double c = 1 / (0.9 * r);  // the shell's probes lie 0.9 r from the core's edge or corner
  const std::array<Probe, 5> probes{{
      {Eigen::Vector3d(0.4 * s, -0.9 * r / std::sqrt(2.0), -0.9 * r / std::sqrt(2.0)), c},  // edge, in the shell
      {Eigen::Vector3d::Constant(-0.9 * r / std::sqrt(3.0)), c},                         // corner, in the shell
      {Eigen::Vector3d(0.4 * s, -0.6 * r, -1.1 * r), 1 / std::hypot(0.6 * r, 1.1 * r)},   // edge, outside it
      {Eigen::Vector3d(0.3 * s, 0.6 * s, -0.5 * r), 0},                                   // face, in the shell
      {Eigen::Vector3d(0.4 * s, 0.01 * s, 0.015 * s), 0}}};                               // inside the core
  const double h = 1e-7 * s;
  for (const Probe& probe : probes) {
    const SignedDistance base = box.signed_distance(probe.q, s);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(base.hessian);
    EXPECT_NEAR(eigen.eigenvalues().cwiseAbs().maxCoeff(), probe.curvature, 1e-9 * c) << probe.q.transpose();
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d up = probe.q, down = probe.q;
      up[i] += h;
      down[i] -= h;
      const SignedDistance a = box.signed_distance(up, s), b = box.signed_distance(down, s);
      EXPECT_NEAR((a.distance - b.distance) / (2 * h), base.normal[i], 1e-6) << probe.q.transpose() << " " << i;
      EXPECT_LT(((a.normal - b.normal) / (2 * h) - base.hessian.col(i)).norm() * r, 1e-5)
          << probe.q.transpose() << " " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(MicrometreAndMetre, ContactKernels, ::testing::Values(1e-4, 1.0));

// A box's sharp features are its 12 edges and 8 corners; a cylinder's its two rims (the side's facets meet at 360/64
// degrees); a 30-degree cone's its apex and base rim (an 80-degree cone's apex is not sharp: its faces' normals
// spread by 20 degrees).
TEST(SharpFeaturePoints, FindEdgesAndCorners) {
  using namespace needlekit::fem::test_support;
  const auto box = box_surface({0, 0, 0}, {1e-3, 2e-3, 3e-3});
  const auto box_points = sharp_feature_points(box, 0.5e-3, 0);
  // Corners + interior points: 4 edges of 1 mm (1 each), 4 of 2 mm (3 each), 4 of 3 mm (5 each); the faces'
  // diagonals are flat.
  EXPECT_EQ(box_points.size(), 8u + 4 * 1 + 4 * 3 + 4 * 5);
  const double r = 100e-6;
  const auto cylinder = placed_needle(flat_cylinder(r, 1e-3), 0, 0, 0, 64);
  const auto rims = sharp_feature_points(cylinder, 1.0, 0);  // spacing larger than any edge: the rims' vertices
  ASSERT_FALSE(rims.empty());
  for (const auto& p : rims) EXPECT_NEAR(std::hypot(p.x(), p.y()), r, 1e-9 * r);
  EXPECT_EQ(sharp_feature_points(cone_surface(0, 0, 80 * M_PI / 180, 50e-6), 1.0, 0).size(), 128u);
  const auto cone = cone_surface(0, 0, 30 * M_PI / 180, 50e-6);
  const auto cone_points = sharp_feature_points(cone, 1.0, 0);
  EXPECT_EQ(cone_points.size(), 129u);  // apex + 128 rim vertices
  EXPECT_EQ(std::count_if(cone_points.begin(), cone_points.end(), [](const auto& p) { return p.norm() == 0; }), 1);
  // With an edge radius, the points move out along the feature's normal: the apex down by it.
  const auto rounded = sharp_feature_points(cone, 1.0, 5e-6);
  EXPECT_EQ(std::count_if(rounded.begin(), rounded.end(),
                          [](const auto& p) { return (p - Eigen::Vector3d(0, 0, -5e-6)).norm() < 1e-12; }),
            1);
}
