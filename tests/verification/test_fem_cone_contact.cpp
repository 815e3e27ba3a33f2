// A rigid cone (half-angle 80 degrees) pressed into a thick block through frictionless surface contact against the
// cone's triangle mesh, vs Sneddon's cone solution F = (2/pi) E/(1 - nu^2) tan(half angle) delta^2 (contact radius
// (2/pi) tan(half angle) delta): the force grows with the square of the depth (the contact area grows), which the
// dissertation's tip-node rule cannot produce for a sharp tip.
#include <gtest/gtest.h>

#include <cmath>

#include "fem_test_support.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::test_support;

TEST(ConeContact, ForceFollowsSneddonsConeSolution) {
  const double core = 100e-6, extent = 8 * core, e = 0.2e6, nu = 0.3, half_angle = 80 * M_PI / 180;
  const auto mesh = quarter_punch_block(core, extent, 3, e, nu);
  SolverOptions o;
  o.boundary = BoundaryCondition::QuarterSymmetry;
  o.contact = ContactModel::Surface;
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
  const double growth = force[3] / force[1];  // depth doubled
  EXPECT_GT(growth, 3.3) << "a sharp cone's force grows like depth^2";
  EXPECT_LT(growth, 4.7);
}
