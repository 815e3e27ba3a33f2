// Bad input to the quasi-static FE solver and the structured block mesher: clear InvalidInput messages naming the
// field and value; and the structured mesh's invariants (volume, orientation, conformity).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <map>

#include "needlekit/core/errors.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"
#include "../support/expect_invalid.hpp"
#include "../verification/fem_test_support.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using needlekit::test::expect_invalid;

namespace {

mesh::TetMesh small_block() {
  mesh::StructuredBlockOptions o;
  o.nx = o.ny = o.nz = 2;
  return mesh::structured_block_mesh(o);
}

Indenter punch(double z_bottom = 0) {
  return {test_support::box_surface({-1e-4, -1e-4, z_bottom}, {1e-4, 1e-4, 1e-3}), {0, 0, -1}};
}

TEST(FemInputs, InvertedAndDegenerateTetrahedraAreRejected) {
  auto m = small_block();
  std::swap(m.tets[3][0], m.tets[3][1]);
  expect_invalid([&] { QuasiStaticSolver(m, {punch()}); }, "tetrahedron 3 is inverted");
  auto d = small_block();
  d.nodes.push_back(d.nodes[0]);
  d.tets[5][2] = static_cast<int>(d.nodes.size()) - 1;
  d.tets[5][0] = 0;
  d.tets[5][1] = static_cast<int>(d.nodes.size()) - 1;
  expect_invalid([&] { QuasiStaticSolver(d, {punch()}); }, "tetrahedron 5 is");
}

TEST(FemInputs, PoissonRatioOfOneHalfIsRejected) {
  auto m = small_block();
  m.layers[0].poisson_ratio = 0.5;
  expect_invalid([&] { QuasiStaticSolver(m, {punch()}); }, "poisson_ratio = 0.5");
}

TEST(FemInputs, NeedleStartingInsideTheTissueIsRejected) {
  expect_invalid([&] { QuasiStaticSolver(small_block(), {punch(-50e-6)}); }, "starts inside the tissue");
}

// max_iterations = 0 takes the contact model's default; a value given is used as given.
TEST(FemInputs, NewtonIterationLimitDependsOnTheContactModelUnlessGiven) {
  SolverOptions o;
  EXPECT_EQ(newton_iteration_limit(o), kNewtonIterations);
  o.contact = ContactModel::Surface;
  EXPECT_EQ(newton_iteration_limit(o), kSurfaceContactNewtonIterations);
  o.max_iterations = 25;
  EXPECT_EQ(newton_iteration_limit(o), 25);
}

TEST(FemInputs, TipNodeRuleNeedsAVerticalNeedleAndOptionsAreChecked) {
  Indenter slanted = punch();
  slanted.direction = {0.3, 0, -1};
  expect_invalid([&] { QuasiStaticSolver(small_block(), {slanted}); }, "direction (0, 0, -1)");
  SolverOptions o;
  o.max_iterations = -1;
  expect_invalid([&] { QuasiStaticSolver(small_block(), {punch()}, o); }, "max_iterations = -1");
  expect_invalid([&] { QuasiStaticSolver(small_block(), {}); }, "no needle");
  expect_invalid([&] { material_law_from_string("hooke"); }, "law: unknown value 'hooke', expected one of: \"neo-hookean\" | \"svk\"");
  EXPECT_EQ(contact_model_from_string("surface"), ContactModel::Surface);
  EXPECT_EQ(boundary_condition_from_string(std::string(to_string(BoundaryCondition::QuarterSymmetry))),
            BoundaryCondition::QuarterSymmetry);
}

TEST(FemInputs, FailedStepKeepsTheLastConvergedStateAndSaysWhy) {
  // A soft block pushed through most of its height with neo-Hookean elements and no cut-backs allowed: the result
  // names the displacement reached and the reason; the solver keeps the last converged state.
  SolverOptions o;
  o.law = MaterialLaw::NeoHookean;
  o.max_cutbacks = 0;
  o.max_iterations = 3;
  QuasiStaticSolver solver(small_block(), {punch()}, o);
  const auto ok = solver.advance_to(1e-6);
  ASSERT_TRUE(ok.converged) << ok.reason;
  const auto bad = solver.advance_to(0.9e-3);
  EXPECT_FALSE(bad.converged);
  EXPECT_NE(bad.reason.find("stopped at 1 um"), std::string::npos) << bad.reason;
  EXPECT_DOUBLE_EQ(solver.indenter_displacement(), 1e-6);
  EXPECT_DOUBLE_EQ(bad.indenter_displacement, 1e-6);
}

TEST(StructuredBlockMesh, VolumesOrientationAndConformity) {
  for (int per_hex : {5, 6}) {
    mesh::StructuredBlockOptions o;
    o.width = 2e-3;
    o.length = 1e-3;
    o.height = 0.5e-3;
    o.nx = 6;
    o.ny = 4;
    o.nz = 3;
    o.tets_per_hex = per_hex;
    o.grading = 4;
    o.focus = {0.3e-3, 0.1e-3};
    const auto m = mesh::structured_block_mesh(o);
    EXPECT_EQ(m.tets.size(), static_cast<size_t>(per_hex * 6 * 4 * 3));
    double volume = 0;
    std::map<std::array<int, 3>, int> faces;
    for (const auto& t : m.tets) {
      const auto& p = m.nodes;
      const double v = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) / 6;
      EXPECT_GT(v, 0);  // right-hand rule
      volume += v;
      for (int f = 0; f < 4; ++f) {
        std::array<int, 3> k{t[f], t[(f + 1) % 4], t[(f + 2) % 4]};
        std::sort(k.begin(), k.end());
        faces[k]++;
      }
    }
    EXPECT_NEAR(volume, 2e-3 * 1e-3 * 0.5e-3, 1e-12 * 1e-9);
    // Conforming: every face is shared by at most two tetrahedra and the boundary faces cover the box's surface.
    double boundary_area = 0;
    for (const auto& [k, n] : faces) {
      EXPECT_LE(n, 2);
      if (n == 1)
        boundary_area += 0.5 * (m.nodes[k[1]] - m.nodes[k[0]]).cross(m.nodes[k[2]] - m.nodes[k[0]]).norm();
    }
    EXPECT_NEAR(boundary_area, 2 * (2e-3 * 1e-3 + 2e-3 * 0.5e-3 + 1e-3 * 0.5e-3), 1e-12);
  }
  mesh::StructuredBlockOptions bad;
  bad.tets_per_hex = 4;
  expect_invalid([&] { mesh::structured_block_mesh(bad); }, "tets_per_hex = 4");
}

}  // namespace
