// Straightest geodesics and the cutting-plane traverse (Algorithm 5.3) against analytic answers: straight lines on
// a plane, unrolled lines on a polygonal cylinder (exact) and helices on the smooth one (second order), great
// circles on a sphere, the vertex rule on a cone, and clean stops at the boundary and at degenerate triangles.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/cutting_plane_trace.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"

using namespace needlekit;
using geometry::PathStatus;
using geometry::SurfaceMesh;
using geometry::SurfacePath;
using testing::HasSubstr;

namespace {

geometry::SurfaceLocation at(const SurfaceMesh& s, const Eigen::Vector3d& p) {
  return geometry::surface_location(s.closest_point(p));
}

// Arc length along the recorded polyline.
double polyline_length(const SurfacePath& path) {
  double sum = 0;
  for (std::size_t i = 1; i < path.points.size(); ++i) sum += (path.points[i] - path.points[i - 1]).norm();
  return sum;
}

// The point at perimeter arc length s (from vertex 0, counter-clockwise) and height z on the polygonal prism of
// open_cylinder_mesh(radius, ..., around, ...).
Eigen::Vector3d prism_point(double radius, int around, double s, double z) {
  const double side = 2 * radius * std::sin(std::numbers::pi / around);
  double k = std::floor(s / side);
  const double fraction = s / side - k;
  const int i = static_cast<int>(std::fmod(std::fmod(k, around) + around, around));
  const auto vertex = [&](int j) {
    const double phi = 2 * std::numbers::pi * j / around;
    return Eigen::Vector3d(radius * std::cos(phi), radius * std::sin(phi), z);
  };
  return vertex(i) + fraction * (vertex(i + 1) - vertex(i));
}

}  // namespace

TEST(StraightestGeodesic, IsTheStraightLineOnAPlaneThroughEdgesAndVertices) {
  for (double scale : {1e-6, 1.0}) {
    const SurfaceMesh plane(test::plane_grid_mesh(scale, 16));
    struct Case {
      Eigen::Vector3d start, direction;
      double length;
    };
    const Case cases[] = {
        {{0.013, -0.021, 0}, {std::cos(0.3), std::sin(0.3), 0}, 0.9},
        {{-0.5, 0, 0}, {1, 0, 0}, 1.25},         // along grid lines, through every vertex on the way
        {{0, 0, 0}, {1, 1, 0}, 0.9},             // from a vertex along the cells' diagonals
        {{0, 0, 0}, {std::cos(0.2), std::sin(0.2), 0}, 0.7},  // from a vertex into a wedge
        {{0.0625, 0.03, 0}, {-1, 0.001, 0}, 0.8},             // starts on an edge, leaving the triangle
        {{0.3, 0.3, 0}, {-0.3, -0.7, 0.5}, 0.6},  // a direction off the plane is projected onto it
    };
    for (const auto& c : cases) {
      const Eigen::Vector3d start = scale * c.start;
      const Eigen::Vector3d d = Eigen::Vector3d(c.direction.x(), c.direction.y(), 0).normalized();
      for (const bool cutting : {false, true}) {
        const auto path = cutting
                              ? geometry::cutting_plane_trace(plane, at(plane, start), c.direction, scale * c.length)
                              : geometry::straightest_geodesic(plane, at(plane, start), c.direction, scale * c.length);
        ASSERT_EQ(path.status, PathStatus::Completed) << path.reason;
        EXPECT_LT((path.end_point - (start + scale * c.length * d)).norm(), 1e-12 * scale)
            << "start " << c.start.transpose() << (cutting ? " (cutting plane)" : "");
        EXPECT_NEAR(path.length, scale * c.length, 1e-12 * scale);
        EXPECT_NEAR(polyline_length(path), scale * c.length, 1e-12 * scale);
        EXPECT_LT((path.end_direction - d).norm(), 1e-10);
        EXPECT_EQ(path.triangles.size() + 1, path.points.size());
        EXPECT_LT((geometry::position(plane, path.end) - path.end_point).norm(), 1e-15 * scale + 1e-300);
      }
    }
  }
}

TEST(StraightestGeodesic, StopsAtTheBoundaryAndAtDegenerateTriangles) {
  const SurfaceMesh plane(test::plane_grid_mesh(1.0, 8));
  const auto path = geometry::straightest_geodesic(plane, at(plane, {0.1, 0.2, 0}), {1, 0, 0}, 5.0);
  EXPECT_EQ(path.status, PathStatus::HitBoundary);
  EXPECT_THAT(path.reason, HasSubstr("boundary"));
  EXPECT_NEAR(path.length, 0.9, 1e-12);
  EXPECT_LT((path.end_point - Eigen::Vector3d(1, 0.2, 0)).norm(), 1e-12);

  // A square whose triangle 1 (4, 5, 2) has no area: vertices 4 and 5 coincide.
  geometry::TriangleMesh sliver;
  sliver.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0, 0}, {0.5, 0, 0}};
  sliver.triangles = {{0, 4, 2}, {4, 5, 2}, {5, 1, 2}, {0, 2, 3}};
  const SurfaceMesh surface(sliver);
  const geometry::SurfaceLocation centroid{0, Eigen::Vector3d(1, 1, 1) / 3};
  for (const bool cutting : {false, true}) {
    const auto stop = cutting ? geometry::cutting_plane_trace(surface, centroid, {1, 0, 0}, 2.0)
                              : geometry::straightest_geodesic(surface, centroid, {1, 0, 0}, 2.0);
    EXPECT_EQ(stop.status, PathStatus::DegenerateTriangle);
    EXPECT_THAT(stop.reason, HasSubstr("triangle 1"));
    EXPECT_NEAR(stop.length, 1.0 / 6, 1e-12);  // from x = 1/2 to the edge 4-2 at x = 2/3
    EXPECT_EQ(stop.end.triangle, 0);
  }
  EXPECT_THROW((void)geometry::straightest_geodesic(plane, at(plane, {0, 0, 0}), {0, 0, 1}, 1.0), InvalidInput);
  EXPECT_THROW((void)geometry::straightest_geodesic(plane, at(plane, {0, 0, 0}), {1, 0, 0}, -1.0), InvalidInput);
  EXPECT_THROW((void)geometry::cutting_plane_trace(plane, {999, {1, 0, 0}}, {1, 0, 0}, 1.0), InvalidInput);
  for (int v : {0, 40, 80}) {
    EXPECT_EQ(geometry::position(plane, geometry::vertex_location(plane, v)), plane.mesh().vertices[v]);
  }
  EXPECT_THROW((void)geometry::vertex_location(plane, 81), InvalidInput);
  geometry::TraceOptions few;
  few.max_steps = 3;  // a 1.8 m walk across the 8 x 8 grid needs more
  const auto cut_short = geometry::straightest_geodesic(plane, at(plane, {-0.9, 0.1, 0}), {1, 0, 0}, 1.8, few);
  EXPECT_EQ(cut_short.status, PathStatus::StepLimit);
  EXPECT_THAT(cut_short.reason, HasSubstr("more than 3 triangles"));
  EXPECT_LT(cut_short.length, 1.8);
  few.max_steps = 0;
  EXPECT_THROW((void)geometry::straightest_geodesic(plane, at(plane, {0, 0, 0}), {1, 0, 0}, 1.0, few), InvalidInput);
}

TEST(StraightestGeodesic, IsExactOnAPolygonalCylinderAndConvergesToTheHelixAtSecondOrder) {
  const double radius = 1.0, height = 4.0, alpha = 0.3, length = 7.0;  // wraps once around
  double previous = 0;
  for (int around : {16, 32, 64, 128}) {
    const SurfaceMesh cylinder(test::open_cylinder_mesh(radius, height, around, 8));
    // Start in the middle of side 0, at z0; unrolled direction at angle alpha from the circumference.
    const double side = 2 * radius * std::sin(std::numbers::pi / around);
    const double z0 = 1.1;
    const Eigen::Vector3d start = prism_point(radius, around, 0.5 * side, z0);
    const Eigen::Vector3d tangent =
        (prism_point(radius, around, side, z0) - prism_point(radius, around, 0, z0)).normalized();
    const Eigen::Vector3d direction = std::cos(alpha) * tangent + std::sin(alpha) * Eigen::Vector3d::UnitZ();
    const auto path = geometry::straightest_geodesic(cylinder, at(cylinder, start), direction, length);
    ASSERT_EQ(path.status, PathStatus::Completed) << path.reason;
    // Exact on the prism, which is intrinsically flat: the unrolled straight line.
    const Eigen::Vector3d exact =
        prism_point(radius, around, 0.5 * side + length * std::cos(alpha), z0 + length * std::sin(alpha));
    EXPECT_LT((path.end_point - exact).norm(), 1e-11) << around;
    // Against the smooth cylinder's helix: the prism's perimeter is short by O(h^2).
    const double phi = (0.5 * side + length * std::cos(alpha)) / radius;
    const Eigen::Vector3d helix(radius * std::cos(phi), radius * std::sin(phi), z0 + length * std::sin(alpha));
    const double error = (path.end_point - helix).norm();
    if (previous > 0) {
      const double order = std::log2(previous / error);
      EXPECT_NEAR(order, 2.0, 0.15) << around;
    }
    previous = error;
  }
  // Straight up a generator: the open top ends the path.
  const SurfaceMesh cylinder(test::open_cylinder_mesh(radius, height, 24, 8));
  const auto up = geometry::straightest_geodesic(cylinder, at(cylinder, {radius, 0.05, 1.0}), {0, 0, 1}, 10.0);
  EXPECT_EQ(up.status, PathStatus::HitBoundary);
  EXPECT_NEAR(up.length, 3.0, 1e-12);
}

TEST(StraightestGeodesic, LeavesAConeApexAtHalfItsTotalAngle) {
  // A cone of n triangles around an apex at height h over a regular n-gon of radius r: arriving along the median
  // of triangle 0, the path leaves at half the apex angle, i.e. along the median of triangle n/2.
  const int n = 10;
  const double r = 1.0, h = 0.7;
  geometry::TriangleMesh cone;
  cone.vertices.push_back({0, 0, h});
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * std::numbers::pi * i / n;
    cone.vertices.push_back({r * std::cos(phi), r * std::sin(phi), 0});
  }
  for (int i = 0; i < n; ++i) cone.triangles.push_back({0, 1 + i, 1 + (i + 1) % n});
  const SurfaceMesh surface(cone);
  const auto midpoint = [&](int i) { return 0.5 * (cone.vertices[1 + i] + cone.vertices[1 + (i + 1) % n]); };
  const Eigen::Vector3d apex = cone.vertices[0];
  const double median = (midpoint(0) - apex).norm();
  const geometry::SurfaceLocation start{0, Eigen::Vector3d(0.1, 0.45, 0.45)};
  const Eigen::Vector3d p = geometry::position(surface, start);
  const auto path = geometry::straightest_geodesic(surface, start, apex - p, 10.0);
  EXPECT_EQ(path.status, PathStatus::HitBoundary);
  EXPECT_LT((path.end_point - midpoint(n / 2)).norm(), 1e-12);
  EXPECT_NEAR(path.length, (apex - p).norm() + median, 1e-12);
  // Starting at the apex itself: the polar map carries the direction to the wedge it points into.
  const geometry::SurfaceLocation top{3, Eigen::Vector3d(1, 0, 0)};
  const auto down = geometry::straightest_geodesic(surface, top, midpoint(3) - apex, 0.5 * median);
  ASSERT_EQ(down.status, PathStatus::Completed) << down.reason;
  EXPECT_LT((down.end_point - (apex + 0.5 * (midpoint(3) - apex))).norm(), 1e-12);
}

TEST(GeodesicTrace, FollowsGreatCirclesOnASphereAtSecondOrder) {
  // From a point of the sphere along 12 tangents for one radian each: the great circles' ends R(cos 1 p + sin 1 t).
  // The error is the mean over the directions (single paths converge irregularly with the triangles they cross).
  const double radius = 0.02;
  const Eigen::Vector3d p = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const Eigen::Vector3d t0 = p.cross(Eigen::Vector3d(0.2, 0.9, 0.1)).normalized();
  const Eigen::Vector3d t1 = p.cross(t0);
  double previous[2] = {0, 0};
  for (int level = 3; level <= 6; ++level) {
    const SurfaceMesh sphere(test::icosphere_mesh(radius, level));
    const auto start = at(sphere, radius * p);
    for (const bool cutting : {false, true}) {
      double error = 0;
      for (int k = 0; k < 12; ++k) {
        const double a = 2 * std::numbers::pi * (k + 0.37) / 12;
        const Eigen::Vector3d t = std::cos(a) * t0 + std::sin(a) * t1;
        const auto path = cutting ? geometry::cutting_plane_trace(sphere, start, t, radius)
                                  : geometry::straightest_geodesic(sphere, start, t, radius);
        ASSERT_EQ(path.status, PathStatus::Completed);
        error += (path.end_point - radius * (std::cos(1.0) * p + std::sin(1.0) * t)).norm() / radius / 12;
      }
      double& last = previous[cutting];
      if (level >= 4) {
        // The cutting plane is the great circle's own plane: second order. The straightest geodesic turns at
        // vertices by the discrete curvature there; on the icosphere its ends converge more slowly.
        if (cutting) EXPECT_NEAR(std::log2(last / error), 2.0, 0.3) << level;
        else EXPECT_GT(std::log2(last / error), 0.8) << level;
      }
      last = error;
      if (level == 6) EXPECT_LT(error, cutting ? 1e-4 : 1e-3);
    }
  }
}
