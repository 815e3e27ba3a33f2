// Angled insertion (insertion/indentation.hpp, "Angled insertion"; docs/indentation.md): a cone tilted from the
// skin's normal, with true (surface) contact, on a small structured block so that each run takes a second or two.
// What the physics fixes, independently of the numbers:
//  - at 0 deg the run is the vertical one: the needle placed by the dissertation's half-turn alone, solved directly;
//  - mirror images: the problem mirrored in x (the block's mesh mirrored, the needle tilted to azimuth 180 instead of
//    0) gives the mirrored loads (axial and |moment| equal, lateral x opposite, lateral y equal);
//  - rotating the whole problem (block and needle) by 90 deg about the vertical rotates the lateral force with it;
//  - the lateral force across a cone's axis (its part odd in the tilt) grows with the angle, and the moment about the
//    base is the moment of the resultant acting near the tip.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "needlekit/needle/rounded_edges.hpp"

using namespace needlekit;

namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kLength = 500e-6;  // m, the cone's length

// A block of 1 x 1 x 0.6 mm, a uniform core of 30 um cells around the site at the centre, graded outside (3.6k
// tetrahedra: each run takes a second or two).
mesh::TetMesh cone_block() {
  mesh::StructuredBlockOptions o;
  o.width = o.length = 1000e-6;
  o.height = 600e-6;
  o.core_cells = 3;
  o.core_half_width = 90e-6;
  o.nx = o.ny = 10;
  o.nz = 6;
  o.material = {"gel", 0, 0.2e6, 0.4};
  return mesh::structured_block_mesh(o);
}

// The mesh mirrored in x (x -> -x; two corners of each tetrahedron swapped to keep it right-handed).
mesh::TetMesh mirrored_in_x(mesh::TetMesh m) {
  for (Eigen::Vector3d& p : m.nodes) p.x() = -p.x();
  for (auto& t : m.tets) std::swap(t[2], t[3]);
  return m;
}

// The mesh turned by 90 deg about the vertical: (x, y, z) -> (-y, x, z).
mesh::TetMesh turned_90(mesh::TetMesh m) {
  for (Eigen::Vector3d& p : m.nodes) p = Eigen::Vector3d(-p.y(), p.x(), p.z());
  return m;
}

insertion::IndentationCase cone_case(const mesh::TetMesh& block, double angle, double azimuth) {
  insertion::IndentationCase c;
  c.name = "cone";
  const needle::NeedleGeometry cone{needle::Shape::Cone, 30e-6, 200e-6, 0, kLength};
  c.geometry = cone;
  c.needle_mesh = {32, 4};
  c.needle = needle::needle_surface_mesh(cone, c.needle_mesh);
  c.tissue_mesh = block;
  c.depth = 40e-6;
  c.steps = 2;
  c.angle = angle;
  c.azimuth = azimuth;
  c.solver.law = fem::MaterialLaw::NeoHookean;
  c.solver.contact = fem::ContactModel::Surface;
  c.solver.two_pass = true;
  c.solver.threads = 1;
  return c;
}

struct Loads {
  double axial = 0;                                  // N
  Eigen::Vector3d lateral = Eigen::Vector3d::Zero();  // N
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();   // N m, about the base
};

Loads last_loads(const insertion::IndentationCase& c) {
  const insertion::IndentationResult r = insertion::run_indentation(c);
  EXPECT_EQ(r.status, insertion::IndentationStatus::ReachedDepth) << r.reason;
  if (r.steps.empty()) return {};
  return {r.steps.back().force, r.steps.back().lateral_force, r.steps.back().moment};
}

TEST(AngledIndentation, ZeroAngleIsTheVerticalRun) {
  const mesh::TetMesh block = cone_block();
  const insertion::IndentationCase c = cone_case(block, 0.0, 0.0);
  const insertion::IndentationResult r = insertion::run_indentation(c);
  ASSERT_EQ(r.steps.size(), 2u) << r.reason;
  // The reference: the needle placed as before angled insertion existed, by the half-turn about x alone
  // ((x, y, z) -> (x, -y, L - z), the cone's tip on the axis at the surface), solved directly.
  std::vector<fem::Indenter> placed = insertion::placed_indenters(c);
  ASSERT_EQ(placed.size(), 1u);
  const needle::ErodedNeedle core = needle::eroded_needle(*c.geometry, placed[0].edge_radius);
  fem::Indenter reference;
  reference.surface = needle::needle_surface_mesh(core.core, c.needle_mesh);
  reference.edge_radius = placed[0].edge_radius;
  for (Eigen::Vector3d& v : reference.surface.vertices)
    v = Eigen::Vector3d(v.x(), -v.y(), kLength - (v.z() + core.base_offset));
  fem::QuasiStaticSolver solver(block, {reference}, c.solver);
  for (int k = 1; k <= 2; ++k) {
    const fem::StepResult step = solver.advance_to(c.depth * k / 2);
    ASSERT_TRUE(step.converged) << step.reason;
    EXPECT_NEAR(r.steps[k - 1].force, step.indenter_force[0], 1e-6 * step.indenter_force[0]) << "step " << k;
  }
  // Not asserted: the lateral force at 0 deg. A sharp cone's nodal contact forces are nearly horizontal (a 10 deg
  // half-angle: about six times the axial force) and cancel only as far as the mesh is symmetric; this mesh's split
  // of each hexahedron along one diagonal leaves 15 % of the axial force across the axis at 40 um (measured).
  RecordProperty("lateral_over_axial_at_0_deg", std::to_string(r.steps.back().lateral_force.norm() / r.steps.back().force));
}

TEST(AngledIndentation, MirrorImagesGiveMirroredLoads) {
  const mesh::TetMesh block = cone_block();
  const double angle = 20 * kDeg;
  const Loads towards_x = last_loads(cone_case(block, angle, 0.0));
  const Loads mirrored = last_loads(cone_case(mirrored_in_x(block), angle, 180 * kDeg));
  // The mirrored problem exactly (the cone's mesh is mirror-symmetric in x up to rounding: 32 segments, one at 0
  // deg): the loads agree to the solver's convergence, far inside 1e-3 of the axial force.
  const double tolerance = 1e-3 * towards_x.axial;
  EXPECT_GT(towards_x.lateral.norm(), 0.05 * towards_x.axial) << "a tilted cone is pushed sideways";
  EXPECT_NEAR(mirrored.axial, towards_x.axial, tolerance);
  EXPECT_NEAR(mirrored.lateral.x(), -towards_x.lateral.x(), tolerance);
  EXPECT_NEAR(mirrored.lateral.y(), towards_x.lateral.y(), tolerance);
  EXPECT_NEAR(mirrored.moment.norm(), towards_x.moment.norm(), tolerance * kLength);

}

TEST(AngledIndentation, TurningTheWholeProblemTurnsTheLoads) {
  const mesh::TetMesh block = cone_block();
  const double angle = 20 * kDeg;
  const Loads original = last_loads(cone_case(block, angle, 0.0));
  // Block and needle turned by 90 deg about the vertical through the site: (x, y) -> (-y, x).
  const Loads turned = last_loads(cone_case(turned_90(block), angle, 90 * kDeg));
  const double tolerance = 1e-3 * original.axial;
  EXPECT_NEAR(turned.axial, original.axial, tolerance);
  EXPECT_NEAR(turned.lateral.x(), -original.lateral.y(), tolerance);
  EXPECT_NEAR(turned.lateral.y(), original.lateral.x(), tolerance);
  EXPECT_NEAR(turned.moment.x(), -original.moment.y(), tolerance * kLength);
  EXPECT_NEAR(turned.moment.y(), original.moment.x(), tolerance * kLength);
}

// On one mesh, not mirror-symmetric, the lateral force of a tilt to azimuth 0 and of the same tilt to azimuth 180
// differ by the mesh's asymmetry (the force across the axis at 0 deg, ZeroAngleIsTheVerticalRun); their odd part
// (F_x(0) - F_x(180)) / 2 cancels it to first order and is the tilt's own lateral force: it grows with the angle.
TEST(AngledIndentation, LateralForceGrowsWithTheAngleAndActsNearTheTip) {
  const mesh::TetMesh block = cone_block();
  double previous = 0;  // N
  for (double degrees : {10.0, 20.0}) {
    SCOPED_TRACE(degrees);
    const insertion::IndentationCase c = cone_case(block, degrees * kDeg, 0.0);
    const Loads loads = last_loads(c);
    const Loads other_way = last_loads(cone_case(block, degrees * kDeg, 180 * kDeg));
    const double odd = 0.5 * (loads.lateral.x() - other_way.lateral.x());
    EXPECT_GT(std::abs(odd), previous);
    previous = std::abs(odd);
    RecordProperty("odd_lateral_force_N_at_" + std::to_string(static_cast<int>(degrees)) + "_deg", std::to_string(odd));
    EXPECT_NEAR(loads.lateral.dot(insertion::needle_axis(c)), 0.0, 1e-12 * loads.axial) << "across the axis";
    // The resultant on the needle acts within the contact, at most ~100 um from the tip: its moment about the base
    // is that of the resultant at the tip within 100 um x |F|.
    const Eigen::Vector3d axis = insertion::needle_axis(c);
    const Eigen::Vector3d resultant = loads.lateral - loads.axial * axis;
    const Eigen::Vector3d at_tip = (kLength * axis).cross(resultant);
    EXPECT_LT((loads.moment - at_tip).norm(), 100e-6 * resultant.norm());
  }
}

}  // namespace
