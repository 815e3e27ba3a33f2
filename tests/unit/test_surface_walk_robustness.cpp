// Robustness of the surface walks on the real meshes (the skull has slivers below 5 degrees, the neck an open
// boundary): thousands of random traces keep their invariants and end with a status, never a crash or a stall.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <filesystem>
#include <numbers>
#include <random>

#include "needlekit/geometry/cutting_plane_trace.hpp"
#include "needlekit/geometry/geodesic_distance.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"

using namespace needlekit;
using geometry::PathStatus;
using geometry::SurfaceMesh;

namespace {

const std::filesystem::path kMeshes = NEEDLEKIT_SOURCE_DIR "/data/meshes";

void expect_path_invariants(const SurfaceMesh& s, const geometry::SurfacePath& path, double length) {
  double travelled = 0;
  for (std::size_t i = 1; i < path.points.size(); ++i) travelled += (path.points[i] - path.points[i - 1]).norm();
  EXPECT_NEAR(travelled, path.length, 1e-9 * length);
  EXPECT_EQ(path.triangles.size() + 1, path.points.size());
  EXPECT_NE(path.status, PathStatus::StepLimit) << path.reason;
  if (path.status == PathStatus::Completed) {
    EXPECT_NEAR(path.length, length, 1e-12 * length);
    EXPECT_TRUE(path.reason.empty());
  } else {
    EXPECT_LE(path.length, length * (1 + 1e-12));
    EXPECT_FALSE(path.reason.empty());
  }
  // Every recorded point lies on the surface, in the triangle of its segment.
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    EXPECT_LT(s.closest_point(path.points[i]).distance, 1e-9 * length);
  }
  EXPECT_NEAR(path.end.barycentric.sum(), 1.0, 1e-12);
  EXPECT_GE(path.end.barycentric.minCoeff(), 0.0);
  EXPECT_LT((geometry::position(s, path.end) - path.end_point).norm(), 1e-12 * length);
  EXPECT_NEAR(path.end_direction.norm(), 1.0, 1e-9);
  EXPECT_LT(std::abs(path.end_direction.dot(s.face_normal(path.end.triangle))), 1e-9);
}

}  // namespace

TEST(SurfaceWalkRobustness, RandomTracesOnTheSkullAndNeckKeepTheirInvariants) {
  for (const auto& [file, unit, length] : {std::tuple{"skull_yahoojapan_10k.obj", 15.8e-3, 0.02},
                                           std::tuple{"vh_male_head_neck_loop2.obj", 1.0, 0.05}}) {
    const auto path = kMeshes / file;
    ASSERT_TRUE(std::filesystem::exists(path)) << "missing repository mesh " << path;
    const SurfaceMesh s(geometry::read_triangle_mesh(path, unit));
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> triangle(0, s.triangle_count() - 1);
    std::uniform_real_distribution<double> u(0, 1);
    int boundary = 0;
    for (int k = 0; k < 400; ++k) {
      geometry::SurfaceLocation start{triangle(rng), {u(rng), u(rng), u(rng)}};
      // Every fourth start sits exactly on a vertex, every fourth on an edge.
      if (k % 4 == 1) start.barycentric = {1, 0, 0};
      if (k % 4 == 2) start.barycentric[2] = 0;
      start.barycentric /= start.barycentric.sum();
      const Eigen::Vector3d d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
      if (d.cross(s.face_normal(start.triangle)).norm() < 1e-3) continue;
      for (const bool cutting : {false, true}) {
        const auto p = cutting ? geometry::cutting_plane_trace(s, start, d, length)
                               : geometry::straightest_geodesic(s, start, d, length);
        expect_path_invariants(s, p, length);
        boundary += p.status == PathStatus::HitBoundary;
      }
    }
    if (std::string(file).starts_with("skull")) EXPECT_EQ(boundary, 0);  // closed: nothing to hit
  }
}

TEST(SurfaceWalkRobustness, TracesAlongEdgesAndThroughVerticesOfTheSkull) {
  const auto file = kMeshes / "skull_yahoojapan_10k.obj";
  ASSERT_TRUE(std::filesystem::exists(file)) << "missing repository mesh " << file;
  const SurfaceMesh s(geometry::read_triangle_mesh(file, 15.8e-3));
  const auto& tris = s.mesh().triangles;
  const auto& v = s.mesh().vertices;
  for (int t = 0; t < s.triangle_count(); t += 37) {
    for (int c = 0; c < 3; ++c) {
      // From a vertex straight along one of its edges, and from an edge's midpoint at the opposite corner.
      const Eigen::Vector3d along = v[tris[t][(c + 1) % 3]] - v[tris[t][c]];
      Eigen::Vector3d corner = Eigen::Vector3d::Zero();
      corner[c] = 1;
      const geometry::SurfaceLocation mid{t, Eigen::Vector3d::Constant(0.5) - 0.5 * Eigen::Vector3d::Unit((c + 2) % 3)};
      const Eigen::Vector3d at_corner = v[tris[t][(c + 2) % 3]] - geometry::position(s, mid);
      for (const bool cutting : {false, true}) {
        const auto a = cutting ? geometry::cutting_plane_trace(s, {t, corner}, along, 0.01)
                               : geometry::straightest_geodesic(s, {t, corner}, along, 0.01);
        expect_path_invariants(s, a, 0.01);
        const auto b = cutting ? geometry::cutting_plane_trace(s, mid, at_corner, 0.01)
                               : geometry::straightest_geodesic(s, mid, at_corner, 0.01);
        expect_path_invariants(s, b, 0.01);
        // Along an edge, the path first reaches the edge's other end.
        EXPECT_LT((a.points[1] - v[tris[t][(c + 1) % 3]]).norm(), 1e-9 * along.norm() + 1e-15) << t << " " << c;
      }
    }
  }
}

TEST(SurfaceWalkRobustness, GeodesicDistancesOnTheSkullConvergeAndAreBounded) {
  const auto file = kMeshes / "skull_yahoojapan_10k.obj";
  ASSERT_TRUE(std::filesystem::exists(file)) << "missing repository mesh " << file;
  const SurfaceMesh s(geometry::read_triangle_mesh(file, 15.8e-3));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int converged = 0, total = 0;
  for (int k = 0; k < 60; ++k) {
    const Eigen::Vector3d p =
        s.mesh().vertices[(k * 131) % s.vertex_count()] + 1e-4 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const auto from = geometry::surface_location(s.closest_point(p));
    // A target 8 mm along a straightest geodesic: a path of that length exists, so the distance is at most that.
    const Eigen::Vector3d d(u(rng), u(rng), u(rng));
    const auto traced = geometry::straightest_geodesic(s, from, d, 0.008);
    ASSERT_EQ(traced.status, PathStatus::Completed);
    const auto along = geometry::geodesic_distance(s, from, traced.end);
    ASSERT_EQ(along.status, geometry::DistanceStatus::Converged) << along.reason;
    EXPECT_LE(along.distance, 0.008 * (1 + 1e-9));
    EXPECT_GE(along.distance, along.euclidean * (1 - 1e-12));
    EXPECT_LT(along.miss, 1e-9);
    // A target anywhere within 8 mm in space (it may lie across a suture or an orbit).
    const auto to = geometry::surface_location(s.closest_point(p + 0.008 * Eigen::Vector3d(u(rng), u(rng), u(rng))));
    const auto there = geometry::geodesic_distance(s, from, to);
    ++total;
    if (there.status != geometry::DistanceStatus::Converged) continue;
    ++converged;
    EXPECT_GE(there.distance, there.euclidean * (1 - 1e-12));
    if (there.graph_distance > 0) EXPECT_LE(there.distance, there.graph_distance * (1 + 1e-12));
    EXPECT_LT(there.miss, 1e-9);
  }
  // Paths that bend at two or more vertices are not found (see geodesic_distance.hpp): nearly all others are.
  EXPECT_GE(converged, 0.95 * total);
}
