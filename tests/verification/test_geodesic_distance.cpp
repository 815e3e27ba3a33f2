// Geodesic distances against analytic ones: exact on a plane and on a polygonal cylinder (intrinsically flat),
// second order towards the smooth cylinder's unrolled distance and the sphere's R * angle.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/geometry/geodesic_distance.hpp"

using namespace needlekit;
using geometry::DistanceStatus;
using geometry::SurfaceMesh;

namespace {

geometry::SurfaceLocation at(const SurfaceMesh& s, const Eigen::Vector3d& p) {
  return geometry::surface_location(s.closest_point(p));
}

}  // namespace

TEST(GeodesicDistance, IsTheStraightDistanceOnAPlaneAtEveryScale) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.95, 0.95);
  for (double scale : {1e-6, 1.0}) {
    const SurfaceMesh plane(test::plane_grid_mesh(scale, 12));
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d p(scale * u(rng), scale * u(rng), 0), q(scale * u(rng), scale * u(rng), 0);
      const auto d = geometry::geodesic_distance(plane, at(plane, p), at(plane, q));
      ASSERT_EQ(d.status, DistanceStatus::Converged) << d.reason;
      EXPECT_NEAR(d.distance, (q - p).norm(), 1e-12 * scale);
      EXPECT_NEAR(d.euclidean, (q - p).norm(), 1e-15 * scale);
      EXPECT_LT((d.path.end_point - q).norm(), 1e-11 * scale);
    }
    // Between grid vertices along grid lines and diagonals (paths through vertices and along edges).
    const auto along =
        geometry::geodesic_distance(plane, at(plane, {-0.5 * scale, 0, 0}), at(plane, {0.5 * scale, 0, 0}));
    EXPECT_NEAR(along.distance, scale, 1e-12 * scale);
    const auto diagonal =
        geometry::geodesic_distance(plane, at(plane, {0, 0, 0}), at(plane, {0.5 * scale, 0.5 * scale, 0}));
    EXPECT_NEAR(diagonal.distance, std::sqrt(0.5) * scale, 1e-12 * scale);
  }
}

TEST(GeodesicDistance, IsExactOnAPolygonalCylinderAndSecondOrderToTheSmoothOne) {
  const double radius = 0.01, height = 0.03;
  const double phi_p = 0.1, z_p = 0.004, phi_q = 2.2, z_q = 0.021;  // 2.1 rad apart: the short way round
  double previous = 0;
  for (int around : {24, 48, 96, 192}) {
    const SurfaceMesh cylinder(test::open_cylinder_mesh(radius, height, around, 6));
    const Eigen::Vector3d p(radius * std::cos(phi_p), radius * std::sin(phi_p), z_p);
    const Eigen::Vector3d q(radius * std::cos(phi_q), radius * std::sin(phi_q), z_q);
    const auto from = at(cylinder, p), to = at(cylinder, q);
    const auto d = geometry::geodesic_distance(cylinder, from, to);
    ASSERT_EQ(d.status, DistanceStatus::Converged) << d.reason;
    // The prism unrolls onto a plane: the perimeter arc between the projected points (they lie on the sides in
    // which phi_p and phi_q fall) and the height difference.
    const auto perimeter_arc = [&](const geometry::SurfaceLocation& l) {
      const Eigen::Vector3d x = geometry::position(cylinder, l);
      const double step = 2 * std::numbers::pi / around;
      const int side = static_cast<int>(std::floor(std::atan2(x.y(), x.x()) / step));
      const Eigen::Vector3d v(radius * std::cos(side * step), radius * std::sin(side * step), x.z());
      return side * 2 * radius * std::sin(0.5 * step) + (x - v).norm();
    };
    const double exact_prism = std::hypot(perimeter_arc(to) - perimeter_arc(from), z_q - z_p);
    EXPECT_NEAR(d.distance, exact_prism, 1e-12) << around;
    const double smooth = std::hypot(radius * (phi_q - phi_p), z_q - z_p);
    const double error = std::abs(d.distance - smooth);
    if (previous > 0) EXPECT_NEAR(std::log2(previous / error), 2.0, 0.1) << around;
    previous = error;
  }
}

TEST(GeodesicDistance, ConvergesToTheGreatCircleDistanceOnASphereAtSecondOrder) {
  const double radius = 0.05;
  const Eigen::Vector3d dirs[][2] = {
      {Eigen::Vector3d(0.3, -0.5, 0.8), Eigen::Vector3d(-0.6, 0.2, 0.7)},
      {Eigen::Vector3d(1, 0.1, 0.05), Eigen::Vector3d(0.2, 1, -0.3)},
      {Eigen::Vector3d(-0.2, 0.4, -0.9), Eigen::Vector3d(0.5, 0.5, -0.7)},
      {Eigen::Vector3d(0.6, 0.6, 0.5), Eigen::Vector3d(-0.7, 0.65, 0.3)},
  };
  double previous = 0;
  for (int level = 3; level <= 6; ++level) {
    const SurfaceMesh sphere(test::icosphere_mesh(radius, level));
    double error = 0;
    for (const auto& pair : dirs) {
      const Eigen::Vector3d p = pair[0].normalized(), q = pair[1].normalized();
      const auto d = geometry::geodesic_distance(sphere, at(sphere, radius * p), at(sphere, radius * q));
      ASSERT_EQ(d.status, DistanceStatus::Converged) << d.reason << " level " << level;
      const double exact = radius * std::acos(p.dot(q));
      EXPECT_LE(d.euclidean, d.distance);
      error += std::abs(d.distance - exact) / exact / 4;
    }
    if (previous > 0) EXPECT_NEAR(std::log2(previous / error), 2.0, 0.35) << level;
    previous = error;
    if (level == 6) EXPECT_LT(error, 1e-4);
  }
}

TEST(GeodesicDistance, BendsAtASaddleVertexWhenTheShortestPathMust) {
  // Six triangles around a saddle vertex V (rim alternately 0.5 above and below): its total angle is
  // 6 acos(0.2) = 471 degrees. Points in opposite triangles see more than 180 degrees between them on both sides, so
  // the shortest path runs through V and no straightest geodesic from p reaches q.
  geometry::TriangleMesh saddle;
  saddle.vertices.push_back({0, 0, 0});
  for (int k = 0; k < 6; ++k) {
    saddle.vertices.push_back(
        {std::cos(k * std::numbers::pi / 3), std::sin(k * std::numbers::pi / 3), k % 2 ? -0.5 : 0.5});
  }
  for (int k = 0; k < 6; ++k) saddle.triangles.push_back({0, 1 + k, 1 + (k + 1) % 6});
  const SurfaceMesh surface(saddle);
  const geometry::SurfaceLocation p{0, {0.2, 0.5, 0.3}}, q{3, {0.3, 0.4, 0.3}};
  const double exact = geometry::position(surface, p).norm() + geometry::position(surface, q).norm();
  const auto d = geometry::geodesic_distance(surface, p, q);
  ASSERT_EQ(d.status, DistanceStatus::Converged) << d.reason;
  EXPECT_EQ(d.via_vertex, 0);
  EXPECT_NEAR(d.distance, exact, 1e-12);
  EXPECT_LT((d.path.end_point - geometry::position(surface, q)).norm(), 1e-12);
  geometry::GeodesicDistanceOptions no_detour;
  no_detour.saddle_detour = false;
  EXPECT_EQ(geometry::geodesic_distance(surface, p, q, no_detour).status, DistanceStatus::NotConverged);
}

TEST(GeodesicDistance, RunsBesideCubeCornersNotThroughThem) {
  // From corner 0 to the opposite corner 7 of a cube of side a: two faces unfolded into an a x 2a rectangle,
  // sqrt(5) a. The first shot, along a face diagonal, converges through corners ((1 + sqrt 2) a: a geodesic but not
  // a shortest path, since a corner's total angle is 3 pi / 2), so the search must go on.
  for (double a : {1e-6, 1.0}) {
    const SurfaceMesh cube(test::cube_mesh(a));
    const geometry::SurfaceLocation corner0{0, {1, 0, 0}};  // triangle {0, 2, 1}
    const geometry::SurfaceLocation corner7{3, {0, 1, 0}};  // triangle {5, 7, 6}
    const auto d = geometry::geodesic_distance(cube, corner0, corner7);
    ASSERT_EQ(d.status, DistanceStatus::Converged) << d.reason;
    EXPECT_NEAR(d.distance, std::sqrt(5.0) * a, 1e-12 * a);
    EXPECT_TRUE(d.path.vertex_crossings.empty());
  }
}

TEST(GeodesicDistance, IsSymmetricAndAboveTheChordOnTheNeck) {
  const std::filesystem::path file = NEEDLEKIT_SOURCE_DIR "/data/meshes/vh_male_head_neck_loop2.obj";
  ASSERT_TRUE(std::filesystem::exists(file)) << "missing repository mesh " << file;
  const SurfaceMesh neck(geometry::read_triangle_mesh(file, 1.0));
  const Eigen::Vector3d centre = neck.mesh().vertices[2243];  // anterior neck (README)
  const Eigen::Vector3d n = neck.vertex_normal(2243);
  const Eigen::Vector3d t0 = n.cross(Eigen::Vector3d::UnitY()).normalized(), t1 = n.cross(t0);
  for (int k = 0; k < 8; ++k) {
    // Points 1-8 mm from the centre, as a patch's springs would span.
    const double angle = 0.7 * k, reach = 1e-3 * (1 + k);
    const auto from = geometry::surface_location(neck.closest_point(centre));
    const auto to =
        geometry::surface_location(neck.closest_point(centre + reach * (std::cos(angle) * t0 + std::sin(angle) * t1)));
    const auto there = geometry::geodesic_distance(neck, from, to);
    const auto back = geometry::geodesic_distance(neck, to, from);
    ASSERT_EQ(there.status, DistanceStatus::Converged) << there.reason;
    ASSERT_EQ(back.status, DistanceStatus::Converged) << back.reason;
    EXPECT_GE(there.distance, there.euclidean * (1 - 1e-12));
    EXPECT_LT(there.distance, there.euclidean * 1.05);  // the neck is gently curved at this scale
    EXPECT_NEAR(there.distance, back.distance, 1e-9 * there.distance);
  }
}
