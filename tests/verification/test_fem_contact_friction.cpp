// Surface contact's second pass (the needle's sharp features against the tissue's faces), rounded needles and Coulomb
// friction: the assembled contact tangent against central differences of the assembled forces, and friction's slip
// limit on an inclined interface (NAFEMS CGS-4's closed form).
#include <gtest/gtest.h>

#include <cmath>

#include "fem_test_support.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::test_support;

namespace {
mesh::TetMesh graded_block(double side, int cells) {
  mesh::StructuredBlockOptions o;
  o.width = o.length = o.height = side;
  o.nx = o.ny = o.nz = cells;
  o.tets_per_hex = 5;
  o.grading = 1.5;
  o.focus = {0.1 * side, -0.2 * side};
  o.material = {"gel", 0, 0.2e6, 0.3};
  return mesh::structured_block_mesh(o);
}

// The centroid of a top face of the solver's mesh (three corners at z = 0) near (x, y).
Eigen::Vector3d top_face_centre(const QuasiStaticSolver& solver, double x, double y) {
  Eigen::Vector3d best = Eigen::Vector3d::Constant(1e300);
  for (const auto& tet : solver.elements()) {
    std::vector<Eigen::Vector3d> top;
    for (int a = 0; a < 4; ++a)
      if (std::abs(solver.nodes()[tet[a]].z()) < 1e-12) top.push_back(solver.nodes()[tet[a]]);
    if (top.size() != 3) continue;
    const Eigen::Vector3d c = (top[0] + top[1] + top[2]) / 3;
    if (std::hypot(c.x() - x, c.y() - y) < std::hypot(best.x() - x, best.y() - y)) best = c;
  }
  return best;
}

// The largest relative difference between the tangent's columns and the central differences of the gradient, and
// between the gradient and the differences of the energy, over the free dofs of the nodes within `radius` of the
// axis point `centre` (the contact region; elsewhere the tangent is the elements', checked in test_fem_*).
// Asserts both below 1e-5 and 1e-6 and records them (test properties tangent_error, force_error).
void expect_consistent_tangent(QuasiStaticSolver& solver, const std::vector<Eigen::Vector3d>& u, double d,
                               const Eigen::Vector3d& centre, double radius, double h) {
  const auto base = solver.linearization(u, d);
  EXPECT_TRUE(base.valid);
  std::vector<std::pair<int, int>> free;  // (node, component) in ascending dof order, as linearization's
  std::vector<Eigen::Index> checked;
  const auto& nodes = solver.nodes();
  double zmin = 0;  // BottomFixed: the free dofs are those of the nodes above the bottom
  for (const auto& x : nodes) zmin = std::min(zmin, x.z());
  for (size_t n = 0; n < nodes.size(); ++n) {
    if (nodes[n].z() <= zmin * (1 - 1e-9)) continue;
    for (int i = 0; i < 3; ++i) {
      if (std::hypot(nodes[n].x() - centre.x(), nodes[n].y() - centre.y()) < radius && nodes[n].z() > -radius)
        checked.push_back(static_cast<Eigen::Index>(free.size()));
      free.emplace_back(static_cast<int>(n), i);
    }
  }
  EXPECT_EQ(base.gradient.size(), static_cast<Eigen::Index>(free.size()));
  double tangent_error = 0, force_error = 0;
  for (Eigen::Index k : checked) {
    auto up = u, down = u;
    up[free[k].first][free[k].second] += h;
    down[free[k].first][free[k].second] -= h;
    const auto p = solver.linearization(up, d), m = solver.linearization(down, d);
    const Eigen::VectorXd column = (p.gradient - m.gradient) / (2 * h);
    tangent_error = std::max(tangent_error, (column - base.tangent.col(k)).norm() / base.tangent.col(k).norm());
    force_error = std::max(force_error, std::abs((p.energy - m.energy) / (2 * h) - base.gradient[k]) /
                                            base.gradient.norm());
  }
  EXPECT_GT(checked.size(), 3u);
  EXPECT_LT(tangent_error, 1e-5);
  EXPECT_LT(force_error, 1e-6);
  ::testing::Test::RecordProperty("tangent_error", ::testing::PrintToString(tangent_error));
  ::testing::Test::RecordProperty("force_error", ::testing::PrintToString(force_error));
}
}  // namespace

// A sharp cone's apex pressed into the middle of a tissue face: no tissue node touches the cone, the second pass
// carries the whole force, and its tangent (k grad g grad g^T - P hess g on the face's nodes) is the derivative of
// its forces.
TEST(ContactTangent, NeedleApexOnATissueFaceMatchesFiniteDifferences) {
  const double side = 300e-6;
  SolverOptions o;
  o.law = MaterialLaw::NeoHookean;
  o.boundary = BoundaryCondition::BottomFixed;
  o.contact = ContactModel::Surface;
  o.two_pass = true;
  const auto mesh = graded_block(side, 3);
  QuasiStaticSolver probe(mesh, {{box_surface({-side, -side, side}, {side, side, 2 * side}), {0, 0, -1}}}, o);
  const Eigen::Vector3d apex = top_face_centre(probe, 0.05 * side, 0.02 * side);
  QuasiStaticSolver solver(mesh, {{cone_surface(apex.x(), apex.y(), 30 * M_PI / 180, 0.2 * side), {0.2, 0.1, -1}}}, o);
  const auto r = solver.advance_to(0.02 * side);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_GT(r.indenter_force[0], 0);
  EXPECT_EQ(r.contact_nodes[0], 0) << "the apex alone touches the tissue";
  expect_consistent_tangent(solver, solver.displacement(), 0.025 * side, apex, 0.6 * side, 1e-7 * side);
}

// A flat punch (sharp rim) moving down and sideways with friction 0.3: the tissue nodes under it slide (slip), the
// rim's points press on the faces round it; the tangent of both passes and of the frozen Coulomb law is the
// derivative of their forces, at µm and m scale.
class FrictionTangent : public ::testing::TestWithParam<double> {};
TEST_P(FrictionTangent, BothPassesWithFrictionMatchFiniteDifferences) {
  const double side = GetParam();
  SolverOptions o;
  o.law = MaterialLaw::NeoHookean;
  o.boundary = BoundaryCondition::BottomFixed;
  o.contact = ContactModel::Surface;
  o.two_pass = true;
  o.friction = 0.3;
  const Eigen::Vector3d centre(0.05 * side, 0.03 * side, 0);
  QuasiStaticSolver solver(graded_block(side, 4),
                           {{placed_needle(flat_cylinder(0.4 * side, side), centre.x(), centre.y(), 0, 32),
                             {0.5, 0.0, -1}}},
                           o);
  const auto r = solver.advance_to(0.02 * side);
  ASSERT_TRUE(r.converged) << r.reason;
  ASSERT_GT(r.contact_nodes[0], 0);
  EXPECT_GT(-r.contact_force[0].x(), 0) << "friction resists the sideways motion";
  // Further on, the nodes that were in contact slip well past their bound: no kink within the differences.
  expect_consistent_tangent(solver, solver.displacement(), 0.025 * side, centre, 0.6 * side, 1e-7 * side);
}
INSTANTIATE_TEST_SUITE_P(MicrometreAndMetre, FrictionTangent, ::testing::Values(300e-6, 1.0));

// A ball (a small box rounded by a radius 20 times its size, Indenter::edge_radius) pressed down and sideways
// without friction: nearly every tissue node in contact lies nearest an edge or a corner of the box, where the
// contact normal turns with the node, so the first pass's tangent carries the curvature term -P hess g (k n n^T
// alone is stiffer than the Hessian there, and Newton crawls with expanded steps).
TEST_P(FrictionTangent, RoundedNeedleMatchesFiniteDifferences) {
  const double side = GetParam(), core = 0.01 * side, radius = 0.2 * side;
  SolverOptions o;
  o.law = MaterialLaw::NeoHookean;
  o.boundary = BoundaryCondition::BottomFixed;
  o.contact = ContactModel::Surface;
  const Eigen::Vector3d centre(0.05 * side, 0.03 * side, radius + core);  // the ball's lowest point at z = 0
  Indenter ball{box_surface(centre.array() - core, centre.array() + core), {0.3, 0.0, -1}, radius};
  QuasiStaticSolver solver(graded_block(side, 6), {ball}, o);
  const auto r = solver.advance_to(0.03 * side);
  ASSERT_TRUE(r.converged) << r.reason;
  ASSERT_GE(r.contact_nodes[0], 3);
  expect_consistent_tangent(solver, solver.displacement(), 0.035 * side, centre, 0.6 * side, 1e-7 * side);
}

// NAFEMS CGS-4's slip limit: a block pushed up a rigid plane inclined at alpha needs F/G = (tan alpha + mu) /
// (1 - mu tan alpha) of horizontal force F per vertical load G when it slides (Coulomb: tangential = mu normal
// force on the interface). Here in the interface's frame: the block's top against a rigid plate that presses and
// slides across it, every top node slipping; the plate's resultant gives T/N and, turned by alpha, F/G.
TEST(Friction, SlipLimitOnAnInclinedInterfaceIsTheNafemsClosedForm) {
  const double side = 1e-3, mu = 0.3, tan_alpha = 0.1, closed_form = 0.412371;
  ASSERT_NEAR((tan_alpha + mu) / (1 - mu * tan_alpha), closed_form, 1e-6);
  mesh::StructuredBlockOptions mo;
  mo.width = mo.length = mo.height = side;
  mo.nx = mo.ny = 6;
  mo.nz = 3;
  mo.material = {"block", 0, 1e6, 0.3};
  SolverOptions o;
  o.contact = ContactModel::Surface;
  o.boundary = BoundaryCondition::BottomFixedSidesRoller;  // fixed top nodes would stay inside the plate
  o.friction = mu;
  o.max_augmentations = 30;
  const double beta = 60 * M_PI / 180;  // the plate's path from the normal: sliding 1.7 times its indentation
  QuasiStaticSolver solver(mesh::structured_block_mesh(mo),
                           {{box_surface({-side, -side, 0}, {side, side, side}), {std::sin(beta), 0, -std::cos(beta)}}},
                           o);
  double ratio = 0;
  for (int k = 1; k <= 4; ++k) {
    const auto r = solver.advance_to(0.005 * side * k);
    ASSERT_TRUE(r.converged) << r.reason;
    const Eigen::Vector3d f = r.contact_force[0];
      ASSERT_GT(f.z(), 0);
    const double t_over_n = -f.x() / f.z();
    ratio = (tan_alpha + t_over_n) / (1 - tan_alpha * t_over_n);
    EXPECT_LT(std::abs(f.y()), 1e-4 * f.z()) << "symmetric about y = 0";
  }
  RecordProperty("F_over_G_relative_error", ::testing::PrintToString(ratio / closed_form - 1));
  EXPECT_NEAR(ratio / closed_form, 1.0, 1e-3);
}
