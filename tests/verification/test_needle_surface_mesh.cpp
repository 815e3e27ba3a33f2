// The needle surface mesh is a closed, outward-oriented polyhedron whose volume converges to volume(needle) with
// second order in the circumferential segments, for every shape, solid and hollow, at micrometre and metre scale.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/needle/needle_geometry.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "needlekit/needle/section_properties.hpp"

using namespace needlekit;
using needle::NeedleGeometry;
using needle::NeedleMeshOptions;
using needle::Shape;

namespace {

struct Case {
  std::string name;
  Shape shape;
  double d1, d2, d3, length;  // µm
};

NeedleGeometry geometry_of(const Case& c, double unit = 1e-6) {
  return {c.shape, c.d1 * unit, c.d2 * unit, c.d3 * unit, c.length * unit};
}

std::string case_name(const testing::TestParamInfo<Case>& info) { return info.param.name; }

const std::vector<Case> kCases = {
    {"solid_cylinder", Shape::Cylinder, 120, 120, 0, 500},
    {"hollow_cylinder", Shape::Cylinder, 120, 120, 20, 500},
    {"solid_cone", Shape::Cone, 30, 120, 0, 500},
    {"hollow_cone", Shape::Cone, 30, 120, 20, 500},
    {"solid_bevel", Shape::Bevel, 30, 120, 0, 500},
    {"hollow_bevel_bore_in_bevel_face", Shape::Bevel, 30, 120, 20, 500},  // tip chord x = −30 µm, bore radius 10
    // §6.2: D2 = 230 µm, D3 = 90 µm; sharp D1 (tip chord at x = −15 µm cuts the bore) and blunt D1 (bore in the tip).
    {"solid_bevel_6_2_sharp", Shape::Bevel, 100, 230, 0, 500},
    {"hollow_bevel_6_2_sharp_chord_cuts_bore", Shape::Bevel, 100, 230, 90, 500},
    {"hollow_bevel_6_2_blunt_bore_in_tip_face", Shape::Bevel, 200, 230, 90, 500},
    // The tip chord exactly tangent to the bore, on either side (x_t = ±D3/2).
    {"hollow_bevel_chord_tangent_to_bore_tip_side", Shape::Bevel, 80, 120, 40, 500},
    {"hollow_bevel_chord_tangent_to_bore_bevel_side", Shape::Bevel, 50, 120, 20, 500},
    {"bevel_with_equal_diameters", Shape::Bevel, 120, 120, 20, 500},
};

class NeedleSurfaceMesh : public testing::TestWithParam<Case> {};

double relative_volume_error(const NeedleGeometry& g, int segments) {
  const auto mesh = needle::needle_surface_mesh(g, {segments, 4});
  return geometry::signed_volume(mesh) / needle::volume(g) - 1;
}

// Exact surface area of the needle: base annulus, tip face, bevel face, outer and bore walls (the walls integrated
// numerically around the axis; the wall height min(L, (r − ρ·cos θ)·L/c) has kinks, so many midpoint intervals).
double exact_surface_area(const NeedleGeometry& g) {
  const double length = g.length, r = g.base_diameter / 2, b = g.bore_diameter / 2;
  const double c = g.base_diameter - g.tip_diameter;
  const double base = M_PI * (r * r - b * b);
  if (g.shape == Shape::Cone) {
    const double r1 = g.tip_diameter / 2;
    return base + M_PI * (r1 * r1 - b * b) + M_PI * (r + r1) * std::hypot(r - r1, length) + 2 * M_PI * b * length;
  }
  if (g.shape == Shape::Cylinder || c == 0) return 2 * base + 2 * M_PI * (r + b) * length;
  const double x_tip = r - c;
  const double tip = needle::clipped_disk_moments(r, x_tip).area - needle::clipped_disk_moments(b, x_tip).area;
  const double bevel_projected = M_PI * (r * r - b * b) - tip;
  const double bevel = bevel_projected * std::hypot(1.0, length / c);  // the plane z = (r − x)·L/c
  auto wall = [&](double rho) {
    constexpr int kIntervals = 200000;
    double sum = 0;
    for (int k = 0; k < kIntervals; ++k) {
      const double theta = 2 * M_PI * (k + 0.5) / kIntervals;
      sum += std::min(length, (r - rho * std::cos(theta)) * length / c);
    }
    return rho * sum * 2 * M_PI / kIntervals;
  };
  return base + tip + bevel + wall(r) + (g.hollow() ? wall(b) : 0.0);
}

}  // namespace

TEST_P(NeedleSurfaceMesh, IsClosedOrientedAndOnTheNeedleSurface) {
  const NeedleGeometry g = geometry_of(GetParam());
  for (int segments : {8, 9, 64, 257}) {
    for (int axial : {1, 16}) {
      SCOPED_TRACE(testing::Message() << "segments " << segments << ", axial " << axial);
      const auto mesh = needle::needle_surface_mesh(g, {segments, axial});
      const auto report = geometry::topology_report(mesh);
      EXPECT_TRUE(report.closed);
      EXPECT_TRUE(report.consistently_oriented);
      EXPECT_EQ(report.boundary_edges, 0);
      EXPECT_EQ(report.non_manifold_edges, 0);
      EXPECT_EQ(report.degenerate_triangles, 0);
      EXPECT_GT(geometry::signed_volume(mesh), 0);

      // Every vertex lies on the boundary of the needle solid (section_properties.cpp): 0 <= z <= L, inside the outer
      // circle, outside the bore, on the kept side of the bevel plane, and on at least one of those surfaces.
      const double tol = 1e-12 * g.length, r = g.base_diameter / 2, b = g.bore_diameter / 2;
      for (const auto& v : mesh.vertices) {
        const double s = g.length - v.z();
        const double outer = needle::outer_diameter_at(g, s) / 2, rho = v.head<2>().norm();
        const double x_cut = g.shape == Shape::Bevel ? r - (g.base_diameter - g.tip_diameter) * (1 - s / g.length)
                                                     : outer;
        ASSERT_GE(v.z(), -tol);
        ASSERT_LE(v.z(), g.length + tol);
        ASSERT_LE(rho, outer + tol);
        ASSERT_GE(rho, b - tol);
        ASSERT_LE(v.x(), x_cut + tol);
        const bool on_surface = v.z() < tol || v.z() > g.length - tol || rho > outer - tol ||
                                (g.hollow() && rho < b + tol) || v.x() > x_cut - tol;
        ASSERT_TRUE(on_surface) << v.transpose();
      }
    }
  }
}

TEST_P(NeedleSurfaceMesh, VolumeConvergesWithSecondOrder) {
  const NeedleGeometry g = geometry_of(GetParam());
  std::vector<double> errors;
  for (int segments : {32, 64, 128, 256}) errors.push_back(std::abs(relative_volume_error(g, segments)));
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log2(errors[k - 1] / errors[k]);
    RecordProperty("order_" + std::to_string(32 << k), std::to_string(order));
    EXPECT_GT(order, 1.7) << "from " << (16 << k) << " to " << (32 << k) << " segments";
    EXPECT_LT(order, 2.3) << "from " << (16 << k) << " to " << (32 << k) << " segments";
  }
  RecordProperty("relative_error_256", std::to_string(errors.back()));
  EXPECT_LT(errors.back(), 1e-3);
}

TEST_P(NeedleSurfaceMesh, SurfaceAreaConvergesToTheExactArea) {
  // Catches folded or overlapping face triangulations, which the volume alone could hide.
  const NeedleGeometry g = geometry_of(GetParam());
  const double exact = exact_surface_area(g);
  const double coarse = std::abs(geometry::surface_area(needle::needle_surface_mesh(g, {128, 4})) / exact - 1);
  const double fine = std::abs(geometry::surface_area(needle::needle_surface_mesh(g, {256, 4})) / exact - 1);
  RecordProperty("area_relative_error_256", std::to_string(fine));
  EXPECT_LT(fine, 1e-3);
  EXPECT_GT(coarse / fine, 3.0);
}

TEST_P(NeedleSurfaceMesh, MetreAndMicrometreScalesAgree) {
  // The same needle in micrometres and scaled to a metre-long one: the same connectivity, vertices scaled, and the
  // same relative volume error.
  const Case& c = GetParam();
  const NeedleGeometry small = geometry_of(c, 1e-6), large = geometry_of(c, 1.0 / c.length);
  const double factor = large.length / small.length;
  const auto a = needle::needle_surface_mesh(small, {48, 8}), b = needle::needle_surface_mesh(large, {48, 8});
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.triangles, b.triangles);
  for (std::size_t k = 0; k < a.vertices.size(); ++k) {
    ASSERT_LT((a.vertices[k] * factor - b.vertices[k]).norm(), 1e-12 * large.length);
  }
  EXPECT_NEAR(geometry::signed_volume(a) / needle::volume(small), geometry::signed_volume(b) / needle::volume(large),
              1e-10);
  EXPECT_NEAR(geometry::surface_area(a) * factor * factor / geometry::surface_area(b), 1.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllShapes, NeedleSurfaceMesh, testing::ValuesIn(kCases), case_name);

TEST(NeedleSurfaceMeshOptions, RejectsTooFewSegmentsAndInvalidGeometry) {
  const NeedleGeometry g{Shape::Cone, 30e-6, 120e-6, 0, 500e-6};
  EXPECT_THAT([&] { needle::needle_surface_mesh(g, {7, 4}); },
              testing::ThrowsMessage<InvalidInput>(testing::HasSubstr("circumferential_segments = 7")));
  EXPECT_THAT([&] { needle::needle_surface_mesh(g, {8, 0}); },
              testing::ThrowsMessage<InvalidInput>(testing::HasSubstr("axial_segments = 0")));
  EXPECT_THROW(needle::needle_surface_mesh({Shape::Cone, 130e-6, 120e-6, 0, 500e-6}), InvalidInput);
  EXPECT_THROW(needle::needle_surface_mesh({Shape::Bevel, 30e-6, 120e-6, 30e-6, 500e-6}), InvalidInput);
}

TEST(NeedleSurfaceMeshOptions, ThinBevelWallNeedsEnoughSegments) {
  // D3 = 118 µm in a 120 µm bevel: a wall of 1 µm, which the coarse polygons cannot separate.
  const NeedleGeometry g{Shape::Bevel, 119e-6, 120e-6, 118e-6, 500e-6};
  EXPECT_THAT([&] { needle::needle_surface_mesh(g, {8, 1}); },
              testing::ThrowsMessage<InvalidInput>(testing::HasSubstr("too coarse")));
  const auto mesh = needle::needle_surface_mesh(g, {512, 1});
  EXPECT_TRUE(geometry::topology_report(mesh).closed);
  EXPECT_NEAR(geometry::signed_volume(mesh) / needle::volume(g), 1.0, 1e-3);
}

TEST(NeedleSurfaceMeshOptions, AxialSegmentsRefineTheWallsOnly) {
  // The wall facets are planar, so more axial levels add vertices but leave the volume unchanged.
  const NeedleGeometry g{Shape::Bevel, 100e-6, 230e-6, 90e-6, 500e-6};
  const auto coarse = needle::needle_surface_mesh(g, {64, 1}), fine = needle::needle_surface_mesh(g, {64, 32});
  EXPECT_GT(fine.vertices.size(), coarse.vertices.size());
  EXPECT_NEAR(geometry::signed_volume(fine) / geometry::signed_volume(coarse), 1.0, 1e-13);
  EXPECT_NEAR(geometry::surface_area(fine) / geometry::surface_area(coarse), 1.0, 1e-11);
}
