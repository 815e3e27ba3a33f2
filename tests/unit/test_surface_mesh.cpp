#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "../support/analytic_surfaces.hpp"
#include "../support/scratch_files.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/surface_mesh.hpp"

using namespace needlekit;
using geometry::SurfaceMesh;
using geometry::TriangleMesh;
using testing::HasSubstr;
using test::scratch_directory;
using test::write_text;

namespace {

// Every neighbour link is mutual and goes through the same two vertices in reverse order.
void expect_symmetric_adjacency(const SurfaceMesh& surface) {
  const auto& tris = surface.mesh().triangles;
  for (int t = 0; t < surface.triangle_count(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const int n = surface.neighbor(t, e);
      if (n < 0) continue;
      int back = -1;
      for (int f = 0; f < 3; ++f) {
        if (surface.neighbor(n, f) == t) back = f;
      }
      ASSERT_GE(back, 0) << "triangle " << t << " edge " << e;
      EXPECT_EQ(tris[t][e], tris[n][(back + 1) % 3]);
      EXPECT_EQ(tris[t][(e + 1) % 3], tris[n][back]);
    }
  }
}

int boundary_edge_count(const SurfaceMesh& surface) {
  int count = 0;
  for (int t = 0; t < surface.triangle_count(); ++t) {
    for (int e = 0; e < 3; ++e) count += surface.neighbor(t, e) < 0;
  }
  return count;
}

}  // namespace

TEST(SurfaceMesh, CubeAdjacencyNormalsAndCheck) {
  const SurfaceMesh cube(test::cube_mesh());
  EXPECT_EQ(cube.triangle_count(), 12);
  EXPECT_EQ(cube.vertex_count(), 8);
  expect_symmetric_adjacency(cube);
  EXPECT_EQ(boundary_edge_count(cube), 0);
  const auto& check = cube.check();
  EXPECT_TRUE(check.closed && check.edge_manifold && check.consistently_oriented);
  EXPECT_EQ(check.boundary_edges, 0);
  EXPECT_EQ(check.degenerate_triangles, 0);
  EXPECT_TRUE(check.problems.empty());
  // Face normals point out of the cube: along the outward axis of their face.
  const Eigen::Vector3d centre(0.5, 0.5, 0.5);
  for (int t = 0; t < 12; ++t) {
    const auto& tri = cube.mesh().triangles[t];
    const Eigen::Vector3d c = (cube.mesh().vertices[tri[0]] + cube.mesh().vertices[tri[1]] +
                               cube.mesh().vertices[tri[2]]) / 3.0;
    const Eigen::Vector3d n = cube.face_normal(t);
    EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(n.cwiseAbs().maxCoeff(), 1.0, 1e-15);
    EXPECT_GT(n.dot(c - centre), 0.1);
  }
  // Angle weighting gives each of the three faces at a corner 90 degrees however the face is split: the corner
  // normal is exactly the diagonal direction (an area- or count-weighted normal would not be).
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d expected = (cube.mesh().vertices[k] - centre).normalized();
    EXPECT_LT((cube.vertex_normal(k) - expected).norm(), 1e-14) << "vertex " << k;
  }
  for (int v = 0; v < 8; ++v) {
    const auto& tri = cube.mesh().triangles[cube.vertex_triangle(v)];
    EXPECT_TRUE(tri[0] == v || tri[1] == v || tri[2] == v);
  }
  // The interpolated normal at a corner is the corner normal; in the middle of a face's diagonal it is the blend.
  EXPECT_LT((cube.interpolated_normal(0, {1, 0, 0}) - cube.vertex_normal(0)).norm(), 1e-15);
}

TEST(SurfaceMesh, IcosphereNormalsAreRadialAndConvergeUnderRefinement) {
  double previous_error = 0;
  for (int level = 0; level <= 4; ++level) {
    const double radius = 2.5e-3;
    const Eigen::Vector3d centre(1e-3, -2e-3, 3e-3);
    const SurfaceMesh sphere(test::icosphere_mesh(radius, level, centre));
    expect_symmetric_adjacency(sphere);
    EXPECT_TRUE(sphere.check().closed);
    EXPECT_EQ(sphere.triangle_count(), 20 << (2 * level));
    double error = 0;
    for (int v = 0; v < sphere.vertex_count(); ++v) {
      const Eigen::Vector3d radial = (sphere.mesh().vertices[v] - centre).normalized();
      error = std::max(error, (sphere.vertex_normal(v) - radial).norm());
    }
    for (int t = 0; t < sphere.triangle_count(); ++t) {
      const auto& tri = sphere.mesh().triangles[t];
      EXPECT_GT(sphere.face_normal(t).dot(sphere.mesh().vertices[tri[0]] - centre), 0);
      const Eigen::Vector3d n = sphere.interpolated_normal(t, {0.2, 0.3, 0.5});
      EXPECT_NEAR(n.norm(), 1.0, 1e-14);
    }
    if (level <= 1) {
      EXPECT_LT(error, 1e-13);  // the icosahedron's symmetry makes these vertex normals exactly radial
    } else if (level >= 3) {
      // First order in the maximum norm: the subdivided icosahedron is irregular near its twelve valence-5
      // vertices, so the error only halves with the edge length.
      EXPECT_LT(error, 0.6 * previous_error);
      EXPECT_GT(error, 0.4 * previous_error);
    }
    previous_error = std::max(error, 1e-16);
  }
}

TEST(SurfaceMesh, OpenCylinderHasTwoBoundaryLoopsAndRadialNormals) {
  const int around = 24, along = 5;
  const double radius = 3.0, height = 2.0;
  const SurfaceMesh cylinder(test::open_cylinder_mesh(radius, height, around, along));
  expect_symmetric_adjacency(cylinder);
  EXPECT_EQ(cylinder.check().boundary_edges, 2 * around);
  EXPECT_EQ(boundary_edge_count(cylinder), 2 * around);
  // Each ring of quads touches the boundary with one triangle per quad (the alternating split).
  EXPECT_EQ(cylinder.check().outer_triangles, 2 * around);
  int inner = 0;
  for (int t = 0; t < cylinder.triangle_count(); ++t) inner += cylinder.is_inner(t);
  EXPECT_EQ(inner, cylinder.triangle_count() - 2 * around);
  EXPECT_FALSE(cylinder.check().closed);
  EXPECT_TRUE(cylinder.check().consistently_oriented);
  for (int t = 0; t < cylinder.triangle_count(); ++t) {
    const Eigen::Vector3d n = cylinder.face_normal(t);
    EXPECT_NEAR(n.z(), 0.0, 1e-14);
    const auto& tri = cylinder.mesh().triangles[t];
    const Eigen::Vector3d c = (cylinder.mesh().vertices[tri[0]] + cylinder.mesh().vertices[tri[1]] +
                               cylinder.mesh().vertices[tri[2]]) / 3.0;
    EXPECT_GT(n.dot(Eigen::Vector3d(c.x(), c.y(), 0).normalized()), std::cos(std::numbers::pi / around) - 1e-12);
  }
  // Interior vertices: the normal is exactly radial by the mirror symmetry of the alternating split.
  for (int v = around; v < along * around; ++v) {
    const Eigen::Vector3d p = cylinder.mesh().vertices[v];
    EXPECT_LT((cylinder.vertex_normal(v) - Eigen::Vector3d(p.x(), p.y(), 0).normalized()).norm(), 1e-12);
  }
}

TEST(SurfaceMesh, ClosestPointIsExactOnCubeAndCylinderAtEveryScale) {
  for (double a : {1e-6, 1.0, 1e3}) {
    const SurfaceMesh cube(test::cube_mesh(a));
    const auto above = cube.closest_point(a * Eigen::Vector3d(0.3, 0.6, 2.0));
    EXPECT_LT((above.point - a * Eigen::Vector3d(0.3, 0.6, 1.0)).norm(), 1e-14 * a);
    EXPECT_NEAR(above.distance, a, 1e-14 * a);
    EXPECT_NEAR(cube.face_normal(above.triangle).z(), 1.0, 1e-15);
    const auto& tri = cube.mesh().triangles[above.triangle];
    const Eigen::Vector3d rebuilt = above.barycentric[0] * cube.mesh().vertices[tri[0]] +
                                    above.barycentric[1] * cube.mesh().vertices[tri[1]] +
                                    above.barycentric[2] * cube.mesh().vertices[tri[2]];
    EXPECT_LT((rebuilt - above.point).norm(), 1e-14 * a);
    EXPECT_NEAR(above.barycentric.sum(), 1.0, 1e-14);
    EXPECT_GE(above.barycentric.minCoeff(), -1e-14);

    const auto corner = cube.closest_point(a * Eigen::Vector3d(2, 2, 2));
    EXPECT_LT((corner.point - a * Eigen::Vector3d(1, 1, 1)).norm(), 1e-14 * a);
    EXPECT_NEAR(corner.distance, a * std::sqrt(3.0), 1e-14 * a);

    const auto inside = cube.closest_point(a * Eigen::Vector3d(0.5, 0.45, 0.9));
    EXPECT_NEAR(inside.distance, 0.1 * a, 1e-14 * a);
    EXPECT_NEAR(inside.point.z(), a, 1e-14 * a);
  }
  // A polygonal cylinder: from outside towards a vertex the distance is r - R; towards a facet's middle it is
  // r - R cos(pi/n).
  const int around = 12;
  const double radius = 2.0;
  const SurfaceMesh cylinder(test::open_cylinder_mesh(radius, 4.0, around, 4));
  const auto at_vertex = cylinder.closest_point({5.0, 0.0, 2.0});
  EXPECT_NEAR(at_vertex.distance, 3.0, 1e-13);
  const double half = std::numbers::pi / around;
  const auto at_facet = cylinder.closest_point({5.0 * std::cos(half), 5.0 * std::sin(half), 1.3});
  EXPECT_NEAR(at_facet.distance, 5.0 - radius * std::cos(half), 1e-13);
  EXPECT_NEAR(at_facet.point.z(), 1.3, 1e-13);
}

TEST(SurfaceMesh, FirstHitIsExactAndSkipsTheStartingSurface) {
  for (double a : {1e-6, 1.0}) {
    const SurfaceMesh cube(test::cube_mesh(a));
    const auto from_below = cube.first_hit(a * Eigen::Vector3d(0.3, 0.4, -1.0), {0, 0, 2});
    ASSERT_TRUE(from_below);
    EXPECT_LT((from_below->point - a * Eigen::Vector3d(0.3, 0.4, 0)).norm(), 1e-14 * a);
    EXPECT_NEAR(from_below->distance, a, 1e-14 * a);
    EXPECT_NEAR(cube.face_normal(from_below->triangle).z(), -1.0, 1e-15);

    const auto from_inside = cube.first_hit(a * Eigen::Vector3d(0.5, 0.5, 0.5), {1, 1, 0});
    ASSERT_TRUE(from_inside);
    EXPECT_LT((from_inside->point - a * Eigen::Vector3d(1, 1, 0.5)).norm(), 1e-14 * a);  // the vertical edge
    EXPECT_NEAR(from_inside->distance, a * std::sqrt(0.5), 1e-14 * a);

    EXPECT_FALSE(cube.first_hit(a * Eigen::Vector3d(0.5, 0.5, 2.0), {0, 0, 1}));   // pointing away
    EXPECT_FALSE(cube.first_hit(a * Eigen::Vector3d(2.0, 2.0, 2.0), {1, 0, 0}));   // off to the side
    // A ray starting on the top face: outward it leaves the cube (s > 0 excludes the start), inward it crosses
    // to the bottom face.
    EXPECT_FALSE(cube.first_hit(a * Eigen::Vector3d(0.25, 0.5, 1.0), {0, 0, 1}));
    const auto through = cube.first_hit(a * Eigen::Vector3d(0.25, 0.5, 1.0), {0, 0, -1});
    ASSERT_TRUE(through);
    EXPECT_NEAR(through->distance, a, 1e-14 * a);
  }
  // From the cylinder's axis towards the middle of a facet: R cos(pi/n).
  const int around = 16;
  const SurfaceMesh cylinder(test::open_cylinder_mesh(1.5, 2.0, around, 3));
  const double half = std::numbers::pi / around;
  const auto hit = cylinder.first_hit({0, 0, 0.7}, {std::cos(half), std::sin(half), 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 1.5 * std::cos(half), 1e-13);
  EXPECT_THROW((void)cylinder.first_hit({0, 0, 0}, {0, 0, 0}), InvalidInput);
}

TEST(SurfaceMesh, RefusesFlippedAndNonManifoldMeshesSayingWhere) {
  TriangleMesh flipped = test::cube_mesh();
  std::swap(flipped.triangles[5][1], flipped.triangles[5][2]);
  const auto check = geometry::surface_check(flipped);
  EXPECT_EQ(check.inconsistent_edges, 3);
  EXPECT_FALSE(check.consistently_oriented);
  EXPECT_TRUE(check.edge_manifold);
  EXPECT_THAT(check.problems, HasSubstr("3 inconsistently oriented edges"));
  EXPECT_THAT(check.problems, HasSubstr("triangles"));
  try {
    SurfaceMesh surface(flipped);
    FAIL() << "a flipped triangle must be refused";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr("8 vertices, 12 triangles"));
    EXPECT_THAT(e.what(), HasSubstr("inconsistently oriented"));
    EXPECT_THAT(e.what(), HasSubstr(" 5"));  // names the flipped triangle
  }

  // Three triangles on the edge 0-1: a fin.
  TriangleMesh fin;
  fin.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const auto fin_check = geometry::surface_check(fin);
  EXPECT_EQ(fin_check.non_manifold_edges, 1);
  EXPECT_FALSE(fin_check.edge_manifold);
  EXPECT_THAT(fin_check.problems, HasSubstr("edge 0-1 in 3 triangles: 0, 1, 2"));
  try {
    SurfaceMesh surface(fin);
    FAIL() << "a non-manifold edge must be refused";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr("1 non-manifold edges"));
  }

  EXPECT_THROW(SurfaceMesh(TriangleMesh{}), InvalidInput);
  TriangleMesh bad_index = test::cube_mesh();
  bad_index.triangles[3][2] = 8;
  EXPECT_THAT([&] { SurfaceMesh surface(bad_index); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("triangle 3 refers to vertex 8")));
}

TEST(SurfaceMesh, CountsSplitSeamsAndWeldingClosesThem) {
  // The cube as a triangle soup: every triangle has its own three vertices.
  const TriangleMesh cube = test::cube_mesh();
  TriangleMesh soup;
  for (const auto& t : cube.triangles) {
    const int base = static_cast<int>(soup.vertices.size());
    for (int c : t) soup.vertices.push_back(cube.vertices[c]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  const SurfaceMesh split(soup);
  EXPECT_EQ(split.check().boundary_edges, 36);
  EXPECT_EQ(split.check().coincident_vertices, 36 - 8);
  EXPECT_EQ(split.check().outer_triangles, 12);
  const SurfaceMesh welded(geometry::welded_mesh(soup));
  EXPECT_EQ(welded.vertex_count(), 8);
  EXPECT_TRUE(welded.check().closed);
  EXPECT_EQ(welded.check().coincident_vertices, 0);
  EXPECT_NEAR(geometry::signed_volume(welded.mesh()), 1.0, 1e-15);
}

TEST(SurfaceMesh, AcceptsAndCountsDegenerateTriangles) {
  // A flat square split into two triangles plus a sliver with a repeated vertex position on the boundary edge.
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0, 0}};
  mesh.triangles = {{0, 4, 2}, {4, 1, 2}, {0, 2, 3}};
  const SurfaceMesh ok(mesh);
  EXPECT_EQ(ok.check().degenerate_triangles, 0);
  mesh.vertices.push_back({0.5, 0, 0});  // 5 coincides with 4: triangle 4-5-2 has no area
  mesh.triangles = {{0, 4, 2}, {4, 5, 2}, {5, 1, 2}, {0, 2, 3}};
  const SurfaceMesh sliver(mesh);
  EXPECT_EQ(sliver.check().degenerate_triangles, 1);
  EXPECT_NEAR(sliver.face_normal(1).z(), 1.0, 1e-14);  // borrowed from its corners
}

TEST(SurfaceMesh, ConcurrentQueriesAgreeWithSerialOnes) {
  const SurfaceMesh sphere(test::icosphere_mesh(1.0, 4));
  std::vector<Eigen::Vector3d> queries;
  for (int k = 0; k < 2000; ++k)
    queries.push_back(1.5 * Eigen::Vector3d(std::sin(k), std::cos(3.0 * k), std::sin(7.0 * k)));
  std::vector<double> serial, parallel(queries.size());
  for (const auto& q : queries) serial.push_back(sphere.closest_point(q).distance);
  std::thread other([&] {
    for (std::size_t i = 0; i < queries.size(); i += 2) parallel[i] = sphere.closest_point(queries[i]).distance;
  });
  for (std::size_t i = 1; i < queries.size(); i += 2) parallel[i] = sphere.closest_point(queries[i]).distance;
  other.join();
  EXPECT_EQ(serial, parallel);
}

TEST(SurfaceMesh, MovesKeepTheTree) {
  SurfaceMesh a(test::cube_mesh());
  SurfaceMesh b = std::move(a);
  EXPECT_NEAR(b.closest_point({0.5, 0.5, 3}).distance, 2.0, 1e-14);
}

TEST(ReadTriangleMesh, ReadsEveryFormatScaledByItsUnit) {
  const auto dir = scratch_directory("surface_mesh_formats");
  const TriangleMesh cube = test::cube_mesh();
  std::string obj = "# cube\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n";
  std::string off = "OFF\n8 12 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n";
  std::string ply = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 12\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n";
  std::string stl = "solid cube\n";
  for (const auto& t : cube.triangles) {
    obj += fmt::format("f {}/{}/{} {} {}//{}\n", t[0] + 1, t[0] + 1, t[0] + 1, t[1] + 1, t[2] + 1, t[2] + 1);
    off += fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
    ply += fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
    stl += " facet normal 0 0 0\n  outer loop\n";
    for (int c : t) {
      const auto& p = cube.vertices[c];
      stl += fmt::format("   vertex {} {} {}\n", p.x(), p.y(), p.z());
    }
    stl += "  endloop\n endfacet\n";
  }
  stl += "endsolid cube\n";
  write_text(dir / "cube.obj", obj);
  write_text(dir / "cube.OFF", off);
  write_text(dir / "cube.ply", ply);
  write_text(dir / "cube_ascii.stl", stl);
  geometry::write_stl(cube, dir / "cube_binary.stl");
  // Binary little-endian PLY.
  {
    std::ofstream out(dir / "cube_binary.ply", std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty double x\nproperty double y\n"
           "property double z\nelement face 12\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : cube.vertices) out.write(reinterpret_cast<const char*>(p.data()), 3 * sizeof(double));
    for (const auto& t : cube.triangles) {
      const unsigned char three = 3;
      out.write(reinterpret_cast<const char*>(&three), 1);
      out.write(reinterpret_cast<const char*>(t.data()), 3 * sizeof(int));
    }
  }
  for (const char* name : {"cube.obj", "cube.OFF", "cube.ply", "cube_binary.ply", "cube_ascii.stl",
                           "cube_binary.stl"}) {
    const TriangleMesh mesh = geometry::read_triangle_mesh(dir / name, 1e-3);
    EXPECT_EQ(mesh.vertices.size(), 8u) << name;  // STL corners merged
    EXPECT_EQ(mesh.triangles.size(), 12u) << name;
    EXPECT_NEAR(geometry::signed_volume(mesh), 1e-9, 1e-21) << name;
    const SurfaceMesh surface(mesh);
    EXPECT_TRUE(surface.check().closed) << name;
  }
}

TEST(ReadTriangleMesh, RefusesPolygonsBadIndicesAndUnknownFormatsNamingTheFile) {
  const auto dir = scratch_directory("surface_mesh_bad");
  write_text(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1 2 5\n");
  EXPECT_THAT([&] { (void)geometry::read_triangle_mesh(dir / "quad.obj", 1.0); },
              testing::ThrowsMessage<IoError>(
                  testing::AllOf(HasSubstr("quad.obj"), HasSubstr("1 of 2 faces are not triangles"),
                                 HasSubstr("face 1 has 4 corners"))));
  write_text(dir / "index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  EXPECT_THROW((void)geometry::read_triangle_mesh(dir / "index.off", 1.0), IoError);
  write_text(dir / "garbage.ply", "this is not a ply file\n");
  EXPECT_THAT([&] { (void)geometry::read_triangle_mesh(dir / "garbage.ply", 1.0); },
              testing::ThrowsMessage<IoError>(HasSubstr("garbage.ply")));
  write_text(dir / "mesh.xyz", "0 0 0\n");
  EXPECT_THAT([&] { (void)geometry::read_triangle_mesh(dir / "mesh.xyz", 1.0); },
              testing::ThrowsMessage<IoError>(HasSubstr("expected .obj, .stl, .ply or .off")));
  EXPECT_THAT([&] { (void)geometry::read_triangle_mesh(dir / "missing.obj", 1.0); },
              testing::ThrowsMessage<IoError>(HasSubstr("missing.obj")));
  EXPECT_THROW((void)geometry::read_triangle_mesh(dir / "quad.obj", 0.0), InvalidInput);
}

TEST(ReadTriangleMesh, RealMeshesHaveTheCountsOfTheirReadme) {
  const std::filesystem::path dir = NEEDLEKIT_SOURCE_DIR "/data/meshes";
  ASSERT_TRUE(std::filesystem::exists(dir / "README.md")) << "missing repository mesh " << dir / "README.md";
  struct Expected {
    const char* file;
    std::size_t triangles, vertices;
    bool closed;
    double unit;
    double extent_min, extent_max;  // m, the largest bounding-box side after scaling
  };
  const Expected meshes[] = {
      {"skull_yahoojapan_10k.obj", 10312, 5154, true, 15.8e-3, 0.15, 0.30},
      {"skull_yahoojapan_100k.obj", 100002, 49999, true, 15.8e-3, 0.15, 0.30},
      {"vh_male_skin.obj", 107334, 53669, true, 1.0, 1.7, 1.9},
      {"vh_male_head_neck_loop2.obj", 240272, 120467, false, 1.0, 0.3, 1.0},
  };
  for (const auto& e : meshes) {
    const TriangleMesh mesh = geometry::read_triangle_mesh(dir / e.file, e.unit);
    EXPECT_EQ(mesh.triangles.size(), e.triangles) << e.file;
    EXPECT_EQ(mesh.vertices.size(), e.vertices) << e.file;
    const SurfaceMesh surface(mesh);
    EXPECT_EQ(surface.check().closed, e.closed) << e.file;
    EXPECT_EQ(surface.check().outer_triangles == 0, e.closed) << e.file;
    EXPECT_TRUE(surface.check().consistently_oriented) << e.file;
    EXPECT_EQ(surface.check().degenerate_triangles, 0) << e.file;
    EXPECT_EQ(surface.check().coincident_vertices, 0) << e.file;
    Eigen::AlignedBox3d box;
    for (const auto& v : mesh.vertices) box.extend(v);
    EXPECT_GT(box.sizes().maxCoeff(), e.extent_min) << e.file;
    EXPECT_LT(box.sizes().maxCoeff(), e.extent_max) << e.file;
    if (e.closed) EXPECT_GT(geometry::signed_volume(mesh), 0) << e.file;  // outward normals
  }
}
