// Several needles indent at once (Fig 6.3's arrays): each needle gets its own reaction, contact area and pressure;
// two well-separated flat needles each carry about the force of one needle alone, in both contact models.
#include <gtest/gtest.h>

#include "fem_test_support.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::test_support;

TEST(MultipleNeedles, TwoSeparatedNeedlesEachCarryTheSingleNeedleForce) {
  mesh::StructuredBlockOptions b;
  b.width = 2e-3;
  b.length = b.height = 1e-3;
  b.nx = 20;
  b.ny = b.nz = 10;
  b.material = {"gel", 0, 0.2e6, 0.4};
  const auto mesh = mesh::structured_block_mesh(b);
  const auto needle = flat_cylinder(160e-6, 300e-6);
  for (auto contact : {ContactModel::TipNodes, ContactModel::Surface}) {
    SolverOptions o;
    o.contact = contact;
    const Indenter left{placed_needle(needle, -0.5e-3, 0, 0), {0, 0, -1}};
    const Indenter right{placed_needle(needle, 0.5e-3, 0, 0), {0, 0, -1}};
    QuasiStaticSolver two(mesh, {left, right}, o), one(mesh, {right}, o);
    const auto r2 = two.advance_to(5e-6), r1 = one.advance_to(5e-6);
    ASSERT_TRUE(r2.converged && r1.converged) << r2.reason << r1.reason;
    ASSERT_EQ(r2.indenter_force.size(), 2u);
    EXPECT_GT(r2.indenter_force[0], 0);
    EXPECT_NEAR(r2.indenter_force[0] / r2.indenter_force[1], 1.0, 0.1) << to_string(contact);
    EXPECT_NEAR(r2.indenter_force[1] / r1.indenter_force[0], 1.0, 0.05) << to_string(contact);
    EXPECT_EQ(r2.contact_nodes[1], r1.contact_nodes[0]);
    int flagged_left = 0, flagged_right = 0;
    for (int f : two.contact_flag()) flagged_left += f == 1, flagged_right += f == 2;
    EXPECT_EQ(flagged_left, r2.contact_nodes[0]);
    EXPECT_EQ(flagged_right, r2.contact_nodes[1]);
  }
}
