// A rigid cone (half-angle 80 degrees) pressed into a thick block through frictionless surface contact against the
// cone's triangle mesh, vs Sneddon's cone solution F = (2/pi) E/(1 - nu^2) tan(half angle) delta^2 (contact radius
// (2/pi) tan(half angle) delta; Sneddon, Int. J. Eng. Sci. 3, 1965, the conical punch, with the semi-vertical
// angle): the force grows with the square of the depth (log-log slope 2; the contact area grows), which the
// dissertation's tip-node rule cannot produce for a sharp tip. With the tissue's nodes against the cone, and with the
// second pass (the cone's rim and edges against the tissue's faces) too.
#include <gtest/gtest.h>

#include <cmath>

#include "fem_test_support.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::test_support;

class ConeContact : public ::testing::TestWithParam<bool> {};  // two_pass
TEST_P(ConeContact, ForceFollowsSneddonsConeSolution) {
  const double core = 100e-6, extent = 8 * core, e = 0.2e6, nu = 0.3, half_angle = 80 * M_PI / 180;
  const auto mesh = quarter_punch_block(core, extent, 5, e, nu);
  SolverOptions o;
  o.boundary = BoundaryCondition::QuarterSymmetry;
  o.contact = ContactModel::Surface;
  o.two_pass = GetParam();
  const double corner = -extent / 2;
  QuasiStaticSolver solver(mesh, {{cone_surface(corner, corner, half_angle, 300e-6), {0, 0, -1}}}, o);
  // Final contact radius 0.8 of the uniform core.
  const double depth = 0.8 * core / (2 / M_PI * std::tan(half_angle));
  std::vector<double> force, ratio;
  for (int k = 1; k <= 4; ++k) {
    const auto r = solver.advance_to(depth * k / 4);
    ASSERT_TRUE(r.converged) << r.reason;
    force.push_back(4 * r.indenter_force[0]);
    ratio.push_back(force.back() / sneddon_cone_force(half_angle, e, nu, depth * k / 4));
    EXPECT_LT(r.max_penetration, 0.01 * depth * k / 4);
  }
  EXPECT_NEAR(ratio.back(), 1.0, 0.15) << "F / F_Sneddon at the final depth";
  // Log-log slope by least squares over the last three depths (the first resolves the contact radius by one cell).
  double mean_x = 0, mean_y = 0, sxy = 0, sxx = 0;
  for (int k = 1; k < 4; ++k) mean_x += std::log(k + 1.0) / 3, mean_y += std::log(force[k]) / 3;
  for (int k = 1; k < 4; ++k) {
    sxy += (std::log(k + 1.0) - mean_x) * (std::log(force[k]) - mean_y);
    sxx += (std::log(k + 1.0) - mean_x) * (std::log(k + 1.0) - mean_x);
  }
  const double slope = sxy / sxx;
  EXPECT_NEAR(slope, 2.0, 0.1) << "a sharp cone's force grows like depth^2";
  RecordProperty("ratio", std::to_string(ratio.back()));
  RecordProperty("slope", std::to_string(slope));
}
INSTANTIATE_TEST_SUITE_P(OneAndTwoPasses, ConeContact, ::testing::Bool());
