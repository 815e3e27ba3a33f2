// The Flexi-patch model (§5.5), placement, fit statuses and bad input of the patch capability.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"

namespace needlekit::patch {
namespace {

using ::testing::HasSubstr;

PatchDesignOptions options_of(int n, double width) {
  PatchDesignOptions o;
  o.needles_u = o.needles_v = n;
  o.width_u = o.width_v = width;
  o.needle = {needle::Shape::Cylinder, 70e-6, 70e-6, 0, 400e-6};
  o.material = materials::material_preset("su-8");
  return o;
}

TEST(PatchDesign, GridSpringsAndInnerNodesOfFigure5_6) {
  PatchDesignOptions o = options_of(10, 10e-3);
  o.stiffness_u = 1e3;
  o.stiffness_v = 2e3;
  o.stiffness_diagonal = 0.5e3;
  const PatchDesign d = patch_design(o);
  EXPECT_EQ(d.node_count(), 100);
  EXPECT_DOUBLE_EQ(d.pitch_u, 1e-3);  // Pxy = w/n
  // 2·n·(n−1) structural + 2·(n−1)² shear springs.
  EXPECT_EQ(d.springs.size(), 2u * 10 * 9 + 2u * 81);
  int inner = 0;
  for (bool b : d.inner) inner += b;
  EXPECT_EQ(inner, 64);
  for (const Spring& s : d.springs) {
    const double rest = (d.rest_positions[s.b] - d.rest_positions[s.a]).norm();
    EXPECT_NEAR(s.rest_length, rest, 1e-18);
    if (s.direction == SpringDirection::U) EXPECT_EQ(s.stiffness, 1e3);
    if (s.direction == SpringDirection::V) EXPECT_EQ(s.stiffness, 2e3);
    if (s.direction == SpringDirection::Diagonal || s.direction == SpringDirection::AntiDiagonal) {
      EXPECT_EQ(s.stiffness, 0.5e3);
      EXPECT_NEAR(s.rest_length, std::sqrt(2.0) * 1e-3, 1e-15);
    }
  }
  EXPECT_EQ(neighbors(d, d.node(0, 0)).size(), 3u);
  EXPECT_EQ(neighbors(d, d.node(5, 0)).size(), 5u);
  EXPECT_EQ(neighbors(d, d.node(5, 5)).size(), 8u);
  // Centred: the outermost nodes w/(2n) inside the edges.
  EXPECT_NEAR(d.rest_positions[d.node(0, 0)].x(), -4.5e-3, 1e-15);
}

TEST(PatchDesign, RejectsNonPositiveSpringConstantsAndTooFewNeedles) {
  PatchDesignOptions o = options_of(10, 10e-3);
  o.stiffness_v = 0;
  EXPECT_THAT([&] { patch_design(o); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("patch design stiffness_v = 0 N/m: expected > 0 N/m")));
  o.stiffness_v = -1e3;
  EXPECT_THROW(patch_design(o), InvalidInput);
  o = options_of(1, 10e-3);
  EXPECT_THAT([&] { patch_design(o); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("needles_u = 1: expected in [2, 10000]")));
}

TEST(PatchPlacement, CentreOffTheMeshAndMissingVertexAreClearErrors) {
  const geometry::SurfaceMesh plane(test::plane_grid_mesh(0.01, 8));
  Placement p;
  p.center = {0, 0, 0.02};
  EXPECT_THAT([&] { patch_frame(plane, p, 0.015, 4e-4); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("is 20 mm from the surface")));
  p.center_vertex = 1000;
  EXPECT_THAT([&] { patch_frame(plane, p, 0.015, 4e-4); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("surface.center_vertex: 1000 does not exist")));
  // The underside of the plane cannot be reached from above.
  p.center_vertex.reset();
  p.center = {0, 0, 0};
  p.approach = Approach::MinusZ;
  geometry::TriangleMesh flipped = test::plane_grid_mesh(0.01, 8);
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  EXPECT_THAT([&] { patch_frame(geometry::SurfaceMesh(flipped), p, 0.015, 4e-4); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("faces away from the approach")));
}

TEST(PatchPlacement, FrameIsRightHandedAndTurnsWithTheRotation) {
  const geometry::SurfaceMesh plane(test::plane_grid_mesh(0.01, 8));
  Placement p;
  p.rotation = M_PI / 2;
  const PatchFrame f = patch_frame(plane, p, 0.015, 4e-4);
  EXPECT_NEAR((f.u - Eigen::Vector3d::UnitY()).norm(), 0, 1e-15);
  EXPECT_NEAR((f.u.cross(f.v) + f.approach).norm(), 0, 1e-15);
  EXPECT_NEAR(f.approach_height, 0.015 + 4e-4, 1e-15);
}

TEST(PatchFit, APatchLargerThanTheSurfaceNamesTheNodesOffItAndStillEvaluates) {
  const geometry::SurfaceMesh plane(test::plane_grid_mesh(0.005, 10));  // 10 x 10 mm
  const PatchDesign d = patch_design(options_of(10, 30e-3));              // 30 x 30 mm
  const PatchFrame frame = patch_frame(plane, Placement{}, 0.045, 4e-4);
  const FittedPatch rigid = rigid_fit(plane, d, frame);
  EXPECT_EQ(rigid.status, FitStatus::BoundaryReached);
  EXPECT_EQ(rigid.affected_nodes.size(), 100u - 16u);  // only the 4 x 4 centre nodes are over the 10 mm plane
  EXPECT_THAT(rigid.reason, HasSubstr("hang over the surface's edge"));
  FlexibleFitOptions options;
  options.max_spring_energy = 1;
  const FittedPatch flexible = flexible_fit(plane, d, frame, options);
  EXPECT_EQ(flexible.status, FitStatus::BoundaryReached);
  EXPECT_FALSE(flexible.affected_nodes.empty());
  EXPECT_THAT(flexible.reason, HasSubstr("larger than the reachable surface"));
  const PatchEvaluation e = evaluate_needles(plane, d, rigid);
  int no_surface = 0;
  for (const NeedleState& s : e.needles) no_surface += s.status == "no_surface";
  EXPECT_EQ(no_surface, 84);
  EXPECT_EQ(e.penetrating, 16);
}

TEST(PatchFit, APatchBesideTheSurfaceMissesIt) {
  const geometry::SurfaceMesh plane(test::plane_grid_mesh(0.005, 10));
  const PatchDesign d = patch_design(options_of(4, 4e-3));
  PatchFrame frame = patch_frame(plane, Placement{}, 0.006, 4e-4);
  frame.surface_point.x() += 0.05;  // moved off to the side
  EXPECT_EQ(rigid_fit(plane, d, frame).status, FitStatus::MissesSurface);
  EXPECT_EQ(flexible_fit(plane, d, frame).status, FitStatus::MissesSurface);
  EXPECT_THROW(flexible_fit(plane, d, frame, {.max_spring_energy = 0}), InvalidInput);
}

TEST(PatchFit, ATraverseAcrossDegenerateTrianglesStopsAndNamesTheNodes) {
  // A 20 x 20 mm plane whose column of cells at x = 2-3 mm is squeezed to zero width: zero-area triangles.
  geometry::TriangleMesh mesh = test::plane_grid_mesh(0.01, 20);
  for (auto& v : mesh.vertices) {
    if (std::abs(v.x() - 0.003) < 1e-9) v.x() = 0.002;
  }
  const geometry::SurfaceMesh plane(mesh);
  const PatchDesign d = patch_design(options_of(10, 10e-3));
  Placement p;
  p.center = {-0.0025, 0.0003, 0};
  const FittedPatch fit = flexible_fit(plane, d, patch_frame(plane, p, 0.015, 4e-4), {.max_spring_energy = 1});
  EXPECT_EQ(fit.status, FitStatus::DegenerateSurface);
  EXPECT_THAT(fit.reason, HasSubstr("degenerate triangle"));
  // The traverses into the strip at x = 2 mm (column i = 9) stop there, and so do those that start from a node
  // left in it; the nodes far from it are not named.
  ASSERT_FALSE(fit.affected_nodes.empty());
  bool strip = false;
  for (const int k : fit.affected_nodes) {
    strip = strip || d.column(k) == 9;
    EXPECT_GE(d.column(k), 6) << "node " << k;
  }
  EXPECT_TRUE(strip);
}

TEST(Equilibrium, OnAPlaneThePatchRestsFlatWithZeroSpringEnergy) {
  const geometry::SurfaceMesh plane(test::plane_grid_mesh(0.01, 12));
  const PatchDesign d = patch_design(options_of(6, 6e-3));
  const PatchFrame frame = patch_frame(plane, Placement{}, 0.0085, 4e-4);
  const FittedPatch fit = equilibrium_fit(plane, d, frame);
  ASSERT_EQ(fit.status, FitStatus::Ok) << fit.reason;
  // Each node sinks by f/κ into the penalty contact and stays flat.
  const double kappa = 1e3 * 1e3, sink = 0.0712 / kappa;
  for (const auto& x : fit.positions) EXPECT_NEAR(x.z(), -sink, 1e-3 * sink);
  for (double e : spring_energies(d, fit.positions)) EXPECT_LT(e, 1e-24);
}

TEST(Equilibrium, OnACylinderThePatchWrapsAndBalancesTheLoad) {
  geometry::TriangleMesh mesh = test::open_cylinder_mesh(0.02, 0.04, 256, 16);
  for (auto& v : mesh.vertices) v = Eigen::Vector3d(v.z() - 0.02, v.x(), v.y());
  const geometry::SurfaceMesh cylinder(mesh);
  const PatchDesign d = patch_design(options_of(8, 8e-3));
  Placement p;
  p.center = {0, 0, 0.02};
  const PatchFrame frame = patch_frame(cylinder, p, 0.012, 4e-4);
  const FittedPatch fit = equilibrium_fit(cylinder, d, frame);
  ASSERT_EQ(fit.status, FitStatus::Ok) << fit.reason;
  int touching = 0;
  for (bool b : fit.on_surface) touching += b;
  EXPECT_EQ(touching, 64);  // 0.0712 N per node bends 1 N/mm springs around R = 20 mm
  // Equilibrium is a minimum: moving any node raises the potential.
  const double base = equilibrium_potential(cylinder, d, frame, rigid_fit(cylinder, d, frame).positions, fit.positions, {});
  for (int k : {0, 27, 63}) {
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<Eigen::Vector3d> moved = fit.positions;
      moved[k][axis] += 1e-6;
      EXPECT_GT(equilibrium_potential(cylinder, d, frame, rigid_fit(cylinder, d, frame).positions, moved, {}),
                base - 1e-12);
    }
  }
}

TEST(PatchConfig, ReadsACaseAndNamesBadKeys) {
  const std::string text = R"(
[surface]
mesh = "neck.obj"
unit = "15.8 mm"
center_vertex = 12
rotation = "30 deg"
approach = "normal"
[patch]
kind = "flexible"
size = "20 mm"
needles_per_row = 20
spring_constant = { u = "1 N/mm", v = "2 N/mm", diagonal = "0.5 N/mm" }
max_spring_energy = "0.05 mJ"
[needle]
shape = "cone"
tip_diameter = "70 um"
base_diameter = "300 um"
length = "1000 um"
material = "su-8"
[tissue]
model = "brain"
)";
  const io::PatchCase c = io::parse_patch_case_toml(text, "case.toml", "/data");
  EXPECT_EQ(c.mesh, std::filesystem::path("/data/neck.obj"));
  EXPECT_NEAR(c.mesh_unit, 0.0158, 1e-15);
  EXPECT_EQ(*c.placement.center_vertex, 12);
  EXPECT_NEAR(c.placement.rotation, M_PI / 6, 1e-15);
  EXPECT_EQ(c.placement.approach, Approach::SurfaceNormal);
  EXPECT_EQ(c.fit.kind, PatchKind::Flexible);
  EXPECT_EQ(c.design.needles_u, 20);
  EXPECT_NEAR(c.design.stiffness_v, 2e3, 1e-9);
  EXPECT_NEAR(c.fit.flexible.max_spring_energy, 5e-5, 1e-18);
  EXPECT_EQ(c.design.needle.shape, needle::Shape::Cone);
  EXPECT_EQ(c.evaluation.conditions.tissue.name, "brain");

  auto error_of = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    changed.replace(changed.find(from), from.size(), to);
    try {
      io::parse_patch_case_toml(changed, "case.toml", "/data");
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of("size = \"20 mm\"", "size = 20"), HasSubstr("case.toml:10: key 'patch.size': 20 is a bare number"));
  EXPECT_THAT(error_of("v = \"2 N/mm\"", "v = \"-2 N/mm\""), HasSubstr("'patch.spring_constant.v'"));
  EXPECT_THAT(error_of("kind = \"flexible\"", "kind = \"soft\""), HasSubstr("unknown value 'soft'"));
  EXPECT_THAT(error_of("center_vertex = 12", "center_vertex = 12\ncenter = [\"0 mm\", \"0 mm\", \"0 mm\"]"),
              HasSubstr("given together with center_vertex"));
  EXPECT_THAT(error_of("max_spring_energy = \"0.05 mJ\"", ""), HasSubstr("missing for a flexible patch"));
  EXPECT_THAT(error_of("[tissue]", "[tissues]"), HasSubstr("unknown table 'tissues'"));
  EXPECT_THAT(error_of("length = \"1000 um\"", "length = \"1000\""), HasSubstr("needle.length"));
  // Keys of another kind of patch are errors, not silently ignored.
  EXPECT_THAT(error_of("kind = \"flexible\"\n", "kind = \"rigid\"\n"),
              HasSubstr("key 'patch.max_spring_energy': applies only to kind = \"flexible\", but kind = \"rigid\""));
  EXPECT_THAT(error_of("max_spring_energy = \"0.05 mJ\"", "max_spring_energy = \"0.05 mJ\"\nload = \"0.07 N\""),
              HasSubstr("key 'patch.load': applies only to kind = \"equilibrium\""));
}

}  // namespace
}  // namespace needlekit::patch
