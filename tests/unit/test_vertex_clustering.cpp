// Vertex clustering (geometry/vertex_clustering.hpp) and the body view built on it (io/body_view.hpp): a mesh within
// the budget is kept whole; a finer one is decimated within the budget, at µm and m scale alike, every vertex of the
// result is a vertex of the input (so a picked vertex names one of the full mesh), every input vertex lies within a
// cell's diagonal of one drawn, and the area of a sphere is kept to the order of the cell size.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/vertex_clustering.hpp"
#include "needlekit/io/body_view.hpp"
#include "needlekit/io/json_config.hpp"
#include "needlekit/io/view_arrays.hpp"

namespace needlekit {
namespace {

using ::testing::HasSubstr;

TEST(VertexClustering, AMeshWithinTheBudgetIsKeptWhole) {
  const geometry::TriangleMesh sphere = test::icosphere_mesh(1.0, 2);
  const geometry::ClusteredMesh kept = geometry::clustered_mesh(sphere, 320);
  EXPECT_EQ(kept.cell_size, 0);
  EXPECT_EQ(kept.mesh.triangles.size(), sphere.triangles.size());
  for (std::size_t k = 0; k < kept.source_vertex.size(); ++k) {
    EXPECT_EQ(kept.mesh.vertices[k], sphere.vertices[static_cast<std::size_t>(kept.source_vertex[k])]);
  }
  EXPECT_NEAR(geometry::surface_area(kept.mesh), geometry::surface_area(sphere), 1e-12);
  EXPECT_THROW(geometry::clustered_mesh(sphere, 0), InvalidInput);
}

TEST(VertexClustering, ASphereIsDecimatedWithinTheBudgetOntoItsOwnVerticesAtAnyScale) {
  for (const double radius : {20e-6, 0.1}) {
    const geometry::TriangleMesh sphere = test::icosphere_mesh(radius, 5, {radius, -2 * radius, 0.5 * radius});
    ASSERT_EQ(sphere.triangles.size(), 20480u);
    const geometry::ClusteredMesh c = geometry::clustered_mesh(sphere, 2000);
    EXPECT_LE(c.mesh.triangles.size(), 2000u);
    EXPECT_GE(c.mesh.triangles.size(), 500u) << "the grid is much coarser than the budget needs";
    ASSERT_EQ(c.source_vertex.size(), c.mesh.vertices.size());
    for (std::size_t k = 0; k < c.mesh.vertices.size(); ++k) {
      EXPECT_EQ(c.mesh.vertices[k], sphere.vertices[static_cast<std::size_t>(c.source_vertex[k])]);
    }
    // Each input vertex has its cell's representative within the cell's diagonal.
    const double reach = std::sqrt(3.0) * c.cell_size;
    for (const Eigen::Vector3d& v : sphere.vertices) {
      double nearest = INFINITY;
      for (const Eigen::Vector3d& w : c.mesh.vertices) nearest = std::min(nearest, (v - w).norm());
      EXPECT_LE(nearest, reach);
    }
    // An inscribed polyhedron of edges about h loses area of order (h / r)^2; holes would lose much more.
    const double exact = 4 * std::numbers::pi * radius * radius;
    EXPECT_NEAR(geometry::surface_area(c.mesh) / exact, 1, 0.05) << "cell " << c.cell_size / radius << " r";
    EXPECT_NEAR(geometry::signed_volume(c.mesh) / (4 * std::numbers::pi * std::pow(radius, 3) / 3), 1, 0.08);
  }
}

TEST(VertexClustering, EveryTriangleFacesOutwardAsTheSurfaceItStandsFor) {
  // An ellipsoid (semi-axes 1, 0.5, 0.3) clustered coarsely: corners moved to their cells' representatives can fold a
  // thin triangle over; each kept triangle still faces the way the surface does there (its normal against the
  // ellipsoid's outward normal (x/a^2, y/b^2, z/c^2) at its centroid), as every input triangle does. Without the
  // reorientation 6 and 2 triangles face inward at two of the budgets.
  const Eigen::Vector3d axes(1, 0.5, 0.3);
  geometry::TriangleMesh ellipsoid = test::icosphere_mesh(1.0, 5);
  for (Eigen::Vector3d& v : ellipsoid.vertices) v = v.cwiseProduct(axes);
  const auto inward = [&](const geometry::TriangleMesh& m) {
    int count = 0;
    for (const auto& t : m.triangles) {
      const auto& v = m.vertices;
      const Eigen::Vector3d outward = (v[t[0]] + v[t[1]] + v[t[2]]).cwiseQuotient(axes.cwiseProduct(axes));
      // Facing away by more than a hair: a sliver standing edge-on (cosine within 0.01 of 0) shows either way.
      count += (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).normalized().dot(outward.normalized()) < -0.01;
    }
    return count;
  };
  ASSERT_EQ(inward(ellipsoid), 0);
  for (const int budget : {3000, 1200, 400, 150}) {
    EXPECT_EQ(inward(geometry::clustered_mesh(ellipsoid, budget).mesh), 0) << budget << " triangles";
  }
}

TEST(BodyView, DrawsTheDecimatedSurfaceWithTheFullMeshsVertexOfEveryVertex) {
  const geometry::SurfaceMesh sphere(test::icosphere_mesh(0.05, 5));
  const nlohmann::json view = io::body_view("sphere", sphere, {.max_triangles = 3000});
  EXPECT_EQ(view["format"], "needlekit-view/1");
  EXPECT_EQ(view["kind"], "body");
  EXPECT_EQ(view["full_mesh"]["triangles"], 20480);
  const std::vector<double> ids = io::decoded_array(view["surface"]["vertex_ids"]);
  const std::vector<double> positions = io::decoded_array(view["surface"]["positions"]);
  const std::vector<double> indices = io::decoded_array(view["surface"]["indices"]);
  ASSERT_EQ(positions.size(), 3 * ids.size());
  EXPECT_EQ(view["surface"]["vertices"], ids.size());
  EXPECT_EQ(3 * view["surface"]["triangles"].get<std::size_t>(), indices.size());
  EXPECT_LE(indices.size(), 3u * 3000);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const Eigen::Vector3d& v = sphere.mesh().vertices[static_cast<std::size_t>(ids[k])];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(positions[3 * k + c], v[c], 1e-7 * 0.05);  // float32
  }
  ASSERT_EQ(view["notes"].size(), 1u);
  EXPECT_THAT(view["notes"][0].get<std::string>(), HasSubstr("decimated by vertex clustering"));
  EXPECT_GT(view["cell_size_m"].get<double>(), 0);
  // Small enough to send as it is: Float32 positions and normals, Uint32 indices and ids, base64.
  EXPECT_LT(view.dump().size(), 4 * (28 * ids.size() + 12 * indices.size() / 3) / 3 + 2000);
  // The full mesh's unit normals at the vertices drawn.
  const std::vector<double> normals = io::decoded_array(view["surface"]["normals"]);
  ASSERT_EQ(normals.size(), 3 * ids.size());
  for (std::size_t k = 0; k < ids.size(); k += 17) {
    const Eigen::Vector3d& n = sphere.vertex_normal(static_cast<int>(ids[k]));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(normals[3 * k + c], n[c], 1e-6);
  }

  const nlohmann::json whole = io::body_view("sphere", sphere, {.max_triangles = 30000});
  EXPECT_EQ(whole["surface"]["triangles"], 20480);
  EXPECT_TRUE(whole["notes"].empty());
}

TEST(BodyView, TheRequestNamesAnOfferedMeshAndItsUnitAsAPatchCaseDoes) {
  const std::map<std::string, std::filesystem::path> meshes{{"neck.obj", "/data/meshes/neck.obj"}};
  const io::BodyMeshFile file =
      io::parse_body_mesh_json(R"({"surface": {"mesh": "neck.obj", "unit": "15.8 mm"}})", "surface.json", meshes);
  EXPECT_EQ(file.mesh, std::filesystem::path("/data/meshes/neck.obj"));
  EXPECT_NEAR(file.mesh_unit, 15.8e-3, 1e-15);
  const auto message = [&](const char* body) {
    try {
      io::parse_body_mesh_json(body, "surface.json", meshes);
    } catch (const std::exception& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(message(R"({"surface": {"mesh": "../../etc/passwd", "unit": "m"}})"),
              HasSubstr("surface.json:1: key 'surface.mesh': '../../etc/passwd' is not one of the meshes offered"));
  EXPECT_THAT(message(R"({"surface": {"mesh": "neck.obj"}})"), HasSubstr("key 'surface.unit'"));
  EXPECT_THAT(message(R"({"surface": {"mesh": "neck.obj", "unit": "2"}})"), HasSubstr("key 'surface.unit'"));
  EXPECT_THAT(message(R"({"surface": {"mesh": "neck.obj", "unit": "m", "center_vertex": 3}})"),
              HasSubstr("center_vertex"));
  EXPECT_THAT(message(R"({"patch": {}})"), HasSubstr("patch"));
}

}  // namespace
}  // namespace needlekit
