// A click on a body's view resolved on the full mesh (geometry/vertex_pick.hpp, io::body_pick, the request
// io::parse_body_pick_json): the vertex named is a corner of the first triangle the ray meets, the nearest one to
// where it meets it, on the side facing the camera; a miss is empty; bad rays name their key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/vertex_pick.hpp"
#include "needlekit/io/body_view.hpp"
#include "needlekit/io/json_config.hpp"

namespace needlekit {
namespace {

using ::testing::HasSubstr;

TEST(VertexPick, TheRayPicksTheNearestCornerOfTheFirstTriangleItMeets) {
  const geometry::SurfaceMesh sphere(test::icosphere_mesh(1.0, 4));
  const auto& vertices = sphere.mesh().vertices;
  for (const Eigen::Vector3d& aim : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.31, -0.22, 0),
                                     Eigen::Vector3d(-0.6, 0.5, 0)}) {
    const Eigen::Vector3d origin = aim + Eigen::Vector3d(0, 0, 5);
    const std::optional<geometry::VertexPick> pick = geometry::pick_vertex(sphere, origin, {0, 0, -3});
    ASSERT_TRUE(pick);
    // Where a unit sphere meets the vertical line through aim, on top (the side facing the ray's origin); the
    // faceted sphere lies within 0.5 % of the radius inside it.
    const double top = std::sqrt(1 - aim.squaredNorm());
    EXPECT_NEAR(pick->point.z(), top, 5e-3);
    EXPECT_NEAR((pick->point - aim).head<2>().norm(), 0, 1e-12);
    // On a regular mesh the nearest corner of the hit triangle is the nearest vertex of all.
    int nearest = 0;
    for (int v = 1; v < sphere.vertex_count(); ++v) {
      if ((vertices[v] - pick->point).norm() < (vertices[nearest] - pick->point).norm()) nearest = v;
    }
    EXPECT_EQ(pick->vertex, nearest);
    const auto& corners = sphere.mesh().triangles[static_cast<std::size_t>(pick->triangle)];
    EXPECT_THAT(corners, ::testing::Contains(pick->vertex));
    EXPECT_GT(vertices[pick->vertex].z(), 0) << "a vertex on the far side";
  }
}

TEST(VertexPick, ARayThatMissesPicksNothingAndABadRayIsRefused) {
  const geometry::SurfaceMesh sphere(test::icosphere_mesh(1.0, 2));
  EXPECT_FALSE(geometry::pick_vertex(sphere, {0, 0, 5}, {0, 0, 1}));
  EXPECT_FALSE(geometry::pick_vertex(sphere, {2, 0, 5}, {0, 0, -1}));
  EXPECT_THROW(geometry::pick_vertex(sphere, {0, 0, 5}, {0, 0, 0}), InvalidInput);
  EXPECT_EQ(io::body_pick(sphere, {0, 0, 5}, {0, 0, 1}), nlohmann::json({{"hit", false}}));
  const nlohmann::json hit = io::body_pick(sphere, {0, 0, 5}, {0, 0, -1});
  EXPECT_TRUE(hit["hit"]);
  EXPECT_GT(hit["normal"][2].get<double>(), 0.9);
}

TEST(VertexPick, TheRequestReadsTheRayWithUnitsAndNamesTheKeyItRefuses) {
  const std::filesystem::path mesh = std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "data/meshes/skull_yahoojapan_10k.obj";
  const std::map<std::string, std::filesystem::path> meshes{{mesh.filename().string(), mesh}};
  const io::BodyPick pick = io::parse_body_pick_json(
      R"({"surface": {"mesh": "skull_yahoojapan_10k.obj", "unit": "mm"},
          "ray": {"origin": ["10 mm", "-2 cm", "0.5 m"], "direction": [0, 0, -2]}})",
      "pick.json", meshes);
  EXPECT_EQ(pick.body.mesh, mesh);
  EXPECT_DOUBLE_EQ(pick.body.mesh_unit, 1e-3);
  EXPECT_TRUE(pick.origin.isApprox(Eigen::Vector3d(0.01, -0.02, 0.5)));
  EXPECT_EQ(pick.direction, Eigen::Vector3d(0, 0, -2));
  const auto refusal = [&](const std::string& ray) {
    try {
      io::parse_body_pick_json(R"({"surface": {"mesh": "skull_yahoojapan_10k.obj", "unit": "mm"}, "ray": )" + ray +
                                   "}",
                               "pick.json", meshes);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal(R"({"origin": ["0 m", "0 m", "1 m"], "direction": [0, 0, 0]})"),
            "pick.json:1: key 'ray.direction': is zero, expected a non-zero vector of three numbers [dx, dy, dz]");
  EXPECT_THAT(refusal(R"({"origin": ["0 m", "0 m", "1 m"], "direction": [0, "down", 0]})"),
              HasSubstr("key 'ray.direction': component 2 is not a finite number"));
  EXPECT_THAT(refusal(R"({"origin": [0, 0, 1], "direction": [0, 0, -1]})"), HasSubstr("key 'ray.origin'"));
  EXPECT_THAT(refusal(R"({"origin": ["0 m", "1 m"], "direction": [0, 0, -1]})"),
              HasSubstr("key 'ray.origin': an array is not a point"));
  EXPECT_THAT(refusal(R"({"direction": [0, 0, -1]})"), HasSubstr("key 'ray.origin': missing"));
}

}  // namespace
}  // namespace needlekit
