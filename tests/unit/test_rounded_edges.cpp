// The eroded core of a needle with rounded edges (needle/rounded_edges.hpp): every face and wall of the core lies at
// distance ρ inside the needle's and parallel to it, so the points within ρ of the core are the needle with its edges
// rounded; out-of-range radii are bad input naming the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "needlekit/core/errors.hpp"
#include "needlekit/needle/rounded_edges.hpp"

using namespace needlekit;
using needle::NeedleGeometry;
using needle::Shape;
using testing::HasSubstr;

namespace {

constexpr double kUm = 1e-6, kRho = 3e-6;

// Signed distance from point (x, z) to the line through (x0, z0) and (x1, z1), and that line's direction.
struct Line {
  double x0, z0, x1, z1;
  double distance(double x, double z) const {
    const double dx = x1 - x0, dz = z1 - z0;
    return ((x - x0) * dz - (z - z0) * dx) / std::hypot(dx, dz);
  }
  double slope() const { return (x1 - x0) / (z1 - z0); }
};

TEST(RoundedEdges, CylinderCoreIsThinnerAndShorterByTheRadius) {
  const NeedleGeometry cylinder{Shape::Cylinder, 230 * kUm, 230 * kUm, 0, 1000 * kUm};
  const needle::ErodedNeedle core = needle::eroded_needle(cylinder, kRho);
  EXPECT_DOUBLE_EQ(core.core.tip_diameter, 230 * kUm - 2 * kRho);
  EXPECT_DOUBLE_EQ(core.core.base_diameter, 230 * kUm - 2 * kRho);
  EXPECT_DOUBLE_EQ(core.core.length, 1000 * kUm - kRho);
  EXPECT_EQ(core.base_offset, 0.0);
  const NeedleGeometry hollow{Shape::Cylinder, 230 * kUm, 230 * kUm, 100 * kUm, 1000 * kUm};
  EXPECT_DOUBLE_EQ(needle::eroded_needle(hollow, kRho).core.bore_diameter, 100 * kUm + 2 * kRho);
  EXPECT_EQ(needle::eroded_needle(cylinder, 0).core.tip_diameter, cylinder.tip_diameter);
}

TEST(RoundedEdges, ConeCoreWallIsParallelAtTheRadius) {
  const NeedleGeometry cone{Shape::Cone, 40 * kUm, 300 * kUm, 0, 600 * kUm};
  const needle::ErodedNeedle e = needle::eroded_needle(cone, kRho);
  EXPECT_EQ(e.base_offset, 0.0);
  EXPECT_DOUBLE_EQ(e.core.length, cone.length - kRho);  // the tip face moved down by ρ
  // The walls in the (r, z) half-plane: tip at z = length, base at z = 0.
  const Line wall{cone.tip_diameter / 2, cone.length, cone.base_diameter / 2, 0};
  const Line core{e.core.tip_diameter / 2, e.core.length, e.core.base_diameter / 2, 0};
  EXPECT_NEAR(core.slope(), wall.slope(), 1e-12);
  EXPECT_NEAR(std::abs(wall.distance(core.x0, core.z0)), kRho, 1e-12 * kRho / kUm);
  EXPECT_NEAR(std::abs(wall.distance(core.x1, core.z1)), kRho, 1e-12 * kRho / kUm);
  EXPECT_LT(core.x0, wall.x0);  // inside
}

TEST(RoundedEdges, BevelCorePlaneIsParallelAtTheRadiusAndMeetsItsCircleBelowTheBase) {
  const NeedleGeometry bevel{Shape::Bevel, 50 * kUm, 230 * kUm, 0, 1000 * kUm};
  const needle::ErodedNeedle e = needle::eroded_needle(bevel, kRho);
  const double r = bevel.base_diameter / 2, rc = e.core.base_diameter / 2;
  EXPECT_DOUBLE_EQ(rc, r - kRho);
  EXPECT_LT(e.base_offset, 0.0);
  EXPECT_NEAR(e.base_offset + e.core.length, bevel.length - kRho, 1e-18);  // the tip face moved down by ρ
  // The cut planes in the (x, z) plane of the needle frame: through the base edge x = r and the tip chord
  // x = D1 - r (needle_geometry.hpp), the core's likewise at its own base z = base_offset.
  const Line plane{r, 0, bevel.tip_diameter - r, bevel.length};
  const Line core{rc, e.base_offset, e.core.tip_diameter - rc, e.base_offset + e.core.length};
  EXPECT_NEAR(core.slope(), plane.slope(), 1e-12);
  EXPECT_NEAR(std::abs(plane.distance(core.x0, core.z0)), kRho, 1e-9 * kRho);
  EXPECT_NEAR(std::abs(plane.distance(core.x1, core.z1)), kRho, 1e-9 * kRho);
  EXPECT_LT(core.x1, plane.x1);  // inside
}

TEST(RoundedEdges, RadiusOutsideItsRangeIsBadInput) {
  const NeedleGeometry cylinder{Shape::Cylinder, 20 * kUm, 20 * kUm, 0, 500 * kUm};
  EXPECT_DOUBLE_EQ(needle::max_edge_radius(cylinder), 10 * kUm);
  EXPECT_THAT([&] { needle::eroded_needle(cylinder, 10 * kUm); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("needle.edge_radius: 10 um")));
  EXPECT_THAT([&] { needle::eroded_needle(cylinder, -1 * kUm); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("needle.edge_radius")));
  const NeedleGeometry hollow{Shape::Cylinder, 20 * kUm, 20 * kUm, 12 * kUm, 500 * kUm};
  EXPECT_DOUBLE_EQ(needle::max_edge_radius(hollow), 2 * kUm);  // a quarter of the 8 um wall
  EXPECT_THROW(needle::eroded_needle(hollow, 2 * kUm), InvalidInput);
  const NeedleGeometry sharp_bevel{Shape::Bevel, 5 * kUm, 230 * kUm, 0, 1000 * kUm};
  EXPECT_DOUBLE_EQ(needle::max_edge_radius(sharp_bevel), 2.5 * kUm);
  EXPECT_NO_THROW(needle::eroded_needle(sharp_bevel, 2 * kUm));
}

TEST(RoundedEdges, DefaultIsTypicalOrHalfTheLargestTheTipAllows) {
  EXPECT_DOUBLE_EQ(needle::default_edge_radius({Shape::Cylinder, 230 * kUm, 230 * kUm, 0, 1000 * kUm}),
                   needle::kTypicalEdgeRadius);
  EXPECT_DOUBLE_EQ(needle::default_edge_radius({Shape::Cone, 3 * kUm, 100 * kUm, 0, 500 * kUm}), 0.75 * kUm);
}

}  // namespace
