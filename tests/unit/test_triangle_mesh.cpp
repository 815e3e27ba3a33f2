#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"

using namespace needlekit;
using geometry::TriangleMesh;
using testing::HasSubstr;
using testing::ThrowsMessage;

namespace {

// The cube [0, a]³ shifted by `origin`, outward-oriented.
TriangleMesh cube(double a = 1.0, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) {
  TriangleMesh mesh;
  for (int k = 0; k < 8; ++k) mesh.vertices.push_back(origin + a * Eigen::Vector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1));
  mesh.triangles = {{0, 2, 1}, {1, 2, 3},   // z = 0, normal −z
                    {4, 5, 6}, {5, 7, 6},   // z = a
                    {0, 1, 4}, {1, 5, 4},   // y = 0
                    {2, 6, 3}, {3, 6, 7},   // y = a
                    {0, 4, 2}, {2, 4, 6},   // x = 0
                    {1, 3, 5}, {3, 7, 5}};  // x = a
  return mesh;
}

// A fresh directory for one test's files.
std::filesystem::path scratch_directory(const std::string& name) {
  const auto dir = std::filesystem::path(testing::TempDir()) / ("needlekit_triangle_mesh_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace

TEST(TriangleMesh, CubeVolumeAndAreaAtEveryScaleAndPosition) {
  for (double a : {1e-6, 1.0, 1e3}) {
    for (const Eigen::Vector3d& origin : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e3 * a, -2e3 * a, 5e2 * a)}) {
      const TriangleMesh mesh = cube(a, origin);
      EXPECT_NEAR(geometry::signed_volume(mesh) / (a * a * a), 1.0, 1e-12) << "a = " << a;
      EXPECT_NEAR(geometry::surface_area(mesh) / (a * a), 6.0, 1e-12) << "a = " << a;
    }
  }
  TriangleMesh inside_out = cube();
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(geometry::signed_volume(inside_out), -1.0, 1e-14);
}

TEST(TriangleMesh, ClosedCubeIsClosedAndOriented) {
  const auto report = geometry::topology_report(cube(1e-6));
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(report.boundary_edges, 0);
  EXPECT_EQ(report.non_manifold_edges, 0);
  EXPECT_EQ(report.degenerate_triangles, 0);
}

TEST(TriangleMesh, RemovingATriangleLeavesThreeBoundaryEdges) {
  TriangleMesh mesh = cube();
  mesh.triangles.pop_back();
  const auto report = geometry::topology_report(mesh);
  EXPECT_FALSE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(report.boundary_edges, 3);
  EXPECT_EQ(report.non_manifold_edges, 0);
}

TEST(TriangleMesh, FlippedTriangleBreaksOrientationButNotClosure) {
  TriangleMesh mesh = cube();
  std::swap(mesh.triangles[4][1], mesh.triangles[4][2]);
  const auto report = geometry::topology_report(mesh);
  EXPECT_TRUE(report.closed);
  EXPECT_FALSE(report.consistently_oriented);
  EXPECT_EQ(report.boundary_edges, 0);
}

TEST(TriangleMesh, FinOnAnEdgeIsNonManifold) {
  TriangleMesh mesh = cube();
  mesh.vertices.emplace_back(0.5, -1.0, 0.0);
  mesh.triangles.push_back({0, 1, 8});  // a third triangle on the cube edge 0–1
  const auto report = geometry::topology_report(mesh);
  EXPECT_FALSE(report.closed);
  EXPECT_FALSE(report.consistently_oriented);
  EXPECT_EQ(report.non_manifold_edges, 1);
  EXPECT_EQ(report.boundary_edges, 2);  // the fin's two free edges
}

TEST(TriangleMesh, DegenerateTrianglesAreCountedRelativeToMeshSize) {
  for (double a : {1e-6, 1.0}) {
    TriangleMesh mesh = cube(a);
    mesh.vertices.push_back(a * Eigen::Vector3d(0.5, 0, 0));  // on the edge 0–1
    mesh.triangles.push_back({0, 1, 8});
    mesh.triangles.push_back({0, 0, 3});
    mesh.triangles.push_back({0, 3, 5});  // a proper (interior) triangle of the same size as the faces
    EXPECT_EQ(geometry::topology_report(mesh).degenerate_triangles, 2) << "a = " << a;
  }
}

TEST(TriangleMesh, RejectsIndicesOutsideTheVertexList) {
  TriangleMesh mesh = cube();
  mesh.triangles[3][2] = 8;
  EXPECT_THAT([&] { geometry::signed_volume(mesh); }, ThrowsMessage<InvalidInput>(HasSubstr("triangle 3")));
  EXPECT_THROW(geometry::topology_report(mesh), InvalidInput);
}

TEST(TriangleMesh, BinaryStlRoundTripMergesVerticesAndScales) {
  const auto dir = scratch_directory("binary");
  const auto path = dir / "cube.stl";
  const TriangleMesh mesh = cube(250e-6, Eigen::Vector3d(1e-3, 0, -5e-4));
  geometry::write_stl(mesh, path, 1e3);  // written in millimetres
  EXPECT_EQ(std::filesystem::file_size(path), 84u + 50u * 12u);
  // Only the target is left behind: the temporary file was renamed.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);

  const TriangleMesh back = geometry::read_stl(path, 1e-3);
  ASSERT_EQ(back.vertices.size(), 8u);
  ASSERT_EQ(back.triangles.size(), 12u);
  EXPECT_NEAR(geometry::signed_volume(back) / geometry::signed_volume(mesh), 1.0, 1e-6);  // float precision
  const auto report = geometry::topology_report(back);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT((back.vertices[back.triangles[t][c]] - mesh.vertices[mesh.triangles[t][c]]).norm(), 1e-10);
    }
  }

  geometry::write_stl(cube(2.0), path);  // overwrites in place
  EXPECT_NEAR(geometry::signed_volume(geometry::read_stl(path)), 8.0, 1e-12);
}

TEST(TriangleMesh, ReadsAsciiStl) {
  const auto dir = scratch_directory("ascii");
  const auto path = dir / "two_cubes.stl";
  // The unit cube, written facet by facet with repeated corners, and a second solid in the same file.
  std::string text = "solid cube exported by hand\n";
  const TriangleMesh mesh = cube();
  for (const auto& t : mesh.triangles) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (int c : t) {
      const auto& v = mesh.vertices[c];
      text += "      vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " +" + std::to_string(v.z());
      text += "\n";
    }
    text += "    endloop\n  endfacet\n";
  }
  text += "endsolid cube\nsolid empty\nendsolid\n";
  write_text(path, text);

  const TriangleMesh back = geometry::read_stl(path, 2.0);
  EXPECT_EQ(back.vertices.size(), 8u);
  EXPECT_EQ(back.triangles.size(), 12u);
  EXPECT_NEAR(geometry::signed_volume(back), 8.0, 1e-12);
  EXPECT_TRUE(geometry::topology_report(back).closed);
}

TEST(TriangleMesh, StlErrorsNameTheFile) {
  const auto dir = scratch_directory("errors");
  const auto missing = dir / "missing.stl";
  EXPECT_THAT([&] { geometry::read_stl(missing); }, ThrowsMessage<IoError>(HasSubstr("missing.stl")));

  // A binary file that lost its last bytes: its size no longer matches 84 + 50·count.
  const auto truncated = dir / "truncated.stl";
  geometry::write_stl(cube(), truncated);
  std::filesystem::resize_file(truncated, 84 + 50 * 12 - 7);
  EXPECT_THAT([&] { geometry::read_stl(truncated); }, ThrowsMessage<IoError>(HasSubstr("truncated.stl")));

  // ASCII errors carry file:line.
  const auto malformed = dir / "malformed.stl";
  write_text(malformed, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\n");
  EXPECT_THAT([&] { geometry::read_stl(malformed); },
              ThrowsMessage<IoError>(HasSubstr("malformed.stl:5: expected a finite number in ASCII STL, got 'zero'")));
  const auto unfinished = dir / "unfinished.stl";
  write_text(unfinished, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
  EXPECT_THAT([&] { geometry::read_stl(unfinished); },
              ThrowsMessage<IoError>(HasSubstr("unfinished.stl:5: unexpected end of ASCII STL, expected 'vertex'")));
  const auto wrong_keyword = dir / "wrong_keyword.stl";
  write_text(wrong_keyword, "solid s\nfacet normal 0 0 1\ninner loop\n");
  EXPECT_THAT([&] { geometry::read_stl(wrong_keyword); },
              ThrowsMessage<IoError>(HasSubstr("wrong_keyword.stl:3: expected 'outer'")));
  const auto not_stl = dir / "notes.txt";
  write_text(not_stl, "hello");
  EXPECT_THAT([&] { geometry::read_stl(not_stl); }, ThrowsMessage<IoError>(HasSubstr("notes.txt: not an STL file")));

  // Writing into a directory that does not exist fails without leaving anything behind.
  const auto unwritable = dir / "no_such_dir" / "out.stl";
  EXPECT_THAT([&] { geometry::write_stl(cube(), unwritable); }, ThrowsMessage<IoError>(HasSubstr("out.stl")));
  EXPECT_FALSE(std::filesystem::exists(dir / "no_such_dir"));
  EXPECT_THROW(geometry::write_stl(cube(), dir / "bad_scale.stl", 0.0), InvalidInput);
}
