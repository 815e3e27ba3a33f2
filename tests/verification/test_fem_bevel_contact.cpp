// Bevel needles (needle_surface_mesh of a Shape::Bevel needle, tip down) and a hollow flat needle pressed into a
// soft block through frictionless surface contact (ContactModel::Surface) on a coarse structured mesh (50 um
// spacing, a few seconds). Before the leading-face rule of RigidSurfaceDistance, a sharp bevel (tip segment 15 um
// wide) gave zero force: the node under the tip was nearest to a side wall once the needle had moved by more than
// half the tip's width, was pushed sideways with a horizontal normal, and the needle slid past it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fem_test_support.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::test_support;

namespace {

constexpr double kR = 115e-6;   // m, outer radius (230 um needle)
constexpr double kL = 300e-6;   // m, needle length
constexpr double kE = 0.2e6;    // Pa, soft gel
constexpr double kNu = 0.4;
constexpr double kTipHeight = 1e-6;  // m, tip above the tissue at zero displacement
const std::vector<double> kDepths{10e-6, 20e-6, 30e-6, 40e-6};

mesh::TetMesh coarse_block() {
  mesh::StructuredBlockOptions b;
  b.width = b.length = 600e-6;
  b.height = 300e-6;
  b.nx = b.ny = 12;
  b.nz = 6;
  b.material = {"gel", 0, kE, kNu};
  return mesh::structured_block_mesh(b);
}

needle::NeedleGeometry bevel(double d1) {
  needle::NeedleGeometry g;
  g.shape = needle::Shape::Bevel;
  g.tip_diameter = d1;
  g.base_diameter = 2 * kR;
  g.length = kL;
  return g;
}

struct Run {
  std::vector<double> force;             // N, per depth
  std::vector<Eigen::Vector3d> contact;  // deformed positions of the contact nodes at the last depth
  bool converged = true;
  std::string reason;
};

// The needle translated by `shift` in x (needle frame x -> tissue x + shift), tip at kTipHeight.
Run indent(const needle::NeedleGeometry& g, double shift) {
  SolverOptions o;
  o.contact = ContactModel::Surface;
  o.law = MaterialLaw::NeoHookean;
  // The default threads: the runs are the same whatever their number (the stalls once seen with several threads came
  // from uninitialised edge normals, docs/fem_solver.md).
  QuasiStaticSolver solver(coarse_block(), {{placed_needle(g, shift, 0, kTipHeight), {0, 0, -1}}}, o);
  Run run;
  for (double d : kDepths) {
    solver.advance_to(d - 5e-6);  // 5 um steps: the first Newton iterate of a step penetrates by a whole step
    const auto r = solver.advance_to(d);
    run.converged = run.converged && r.converged;
    if (!r.converged) run.reason = r.reason;
    run.force.push_back(r.indenter_force[0]);
  }
  for (size_t a = 0; a < solver.nodes().size(); ++a)
    if (solver.contact_flag()[a]) run.contact.push_back(solver.nodes()[a] + solver.displacement()[a]);
  return run;
}

// Height of a bevel's leading surface (tip face, then bevel face) above the tissue-frame point x, with the needle
// shifted by `shift` and displaced by `depth`: the needle-frame bevel plane z = (r - x)L/c becomes
// z = z_tip - depth + max(0, (x_n - x_t) L / c) with x_n = x - shift, x_t = D1 - r, c = D2 - D1.
double leading_height(const needle::NeedleGeometry& g, double shift, double depth, double x) {
  const double c = g.base_diameter - g.tip_diameter, xt = g.tip_diameter - kR;
  return kTipHeight - depth + std::max(0.0, (x - shift - xt) * g.length / c);
}

// `first`: index of the first depth at which the needle touches a node.
void expect_bevel_physics(double d1, double shift, bool on_bevel_face, size_t first = 0) {
  const auto g = bevel(d1);
  const auto run = indent(g, shift);
  ASSERT_TRUE(run.converged) << run.reason;
  for (size_t k = first; k < kDepths.size(); ++k) {
    EXPECT_GT(run.force[k], 0) << "D1 = " << d1 * 1e6 << " um at " << kDepths[k] * 1e6 << " um";
    if (k > first) EXPECT_GT(run.force[k], 1.2 * run.force[k - 1]) << "force grows with depth";
  }
  ASSERT_FALSE(run.contact.empty());
  bool any_on_bevel = false;
  for (const auto& q : run.contact) {
    // On the needle's leading surface (tip face or bevel face), inside its circle; 0.25 um = 5 x the solver's
    // penetration tolerance (1e-3 of the 50 um element size), 0.6% of the depth.
    EXPECT_NEAR(q.z(), leading_height(g, shift, kDepths.back(), q.x()), 0.25e-6) << q.transpose();
    EXPECT_LE(std::hypot(q.x() - shift, q.y()), kR * (1 + 1e-6));
    any_on_bevel = any_on_bevel || q.x() - shift > g.tip_diameter - kR + 1e-6;
  }
  if (on_bevel_face) EXPECT_TRUE(any_on_bevel) << "a contact node on the bevel face";
  // A flat punch of the same outer diameter, same depth: more force.
  const auto flat = indent(flat_cylinder(kR, kL), 0);
  ASSERT_TRUE(flat.converged) << flat.reason;
  for (size_t k = 0; k < kDepths.size(); ++k) EXPECT_LT(run.force[k], flat.force[k]);
}

}  // namespace

// Tip face centred over a node (the insertion runner's placement): the case that gave zero force.
TEST(BevelContact, SharpBevelPushesTheNodeUnderItsTip) { expect_bevel_physics(15e-6, kR - 7.5e-6, false); }
TEST(BevelContact, BluntBevelPushesTheNodeUnderItsTip) { expect_bevel_physics(50e-6, kR - 25e-6, false); }
// Tip chord 10 um before the node at x = 0 (the tip face falls between nodes): that node meets the bevel face, 14 um
// above the tip, between the first two depths.
TEST(BevelContact, SharpBevelFaceLoadsTheNodesItMeets) {
  const auto g = bevel(15e-6);
  const double shift = kR - 25e-6;
  ASSERT_GT(leading_height(g, shift, 0, 0) - kTipHeight, kDepths[0]);
  ASSERT_LT(leading_height(g, shift, 0, 0) - kTipHeight, kDepths[1]);
  expect_bevel_physics(15e-6, shift, true, 1);
}

TEST(BevelContact, HollowFlatNeedleHasNoContactInsideItsBore) {
  auto hollow = flat_cylinder(kR, kL);
  hollow.bore_diameter = 90e-6;
  const auto annulus = indent(hollow, 0), solid = indent(flat_cylinder(kR, kL), 0);
  ASSERT_TRUE(annulus.converged && solid.converged) << annulus.reason << solid.reason;
  ASSERT_FALSE(annulus.contact.empty());
  for (const auto& q : annulus.contact) {
    const double radius = std::hypot(q.x(), q.y());
    EXPECT_GE(radius, 45e-6) << "contact inside the bore at " << q.transpose();
    EXPECT_LE(radius, kR * (1 + 1e-6));
    EXPECT_NEAR(q.z(), kTipHeight - kDepths.back(), 0.25e-6) << "on the annular tip face";
  }
  // The solid punch also loads the node on the axis (inside the bore's circle): more force, same growth.
  for (size_t k = 0; k < kDepths.size(); ++k) {
    EXPECT_GT(annulus.force[k], 0);
    EXPECT_LT(annulus.force[k], solid.force[k]);
  }
  EXPECT_NEAR(annulus.force[3] / annulus.force[1], solid.force[3] / solid.force[1], 0.1);
}
