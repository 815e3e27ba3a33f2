// The surface readers on the inputs issue 16 found crashing or exhausting memory (now replayed by the fuzz
// regression corpus too), on PLY's scalar types and byte orders, and the body-surface checks: inward-facing closed
// surfaces are turned outwards, degenerate triangles refused with how many and where, directories refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstring>
#include <functional>
#include <filesystem>
#include <string>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit {
namespace {

using geometry::MeshFormat;
using geometry::parse_triangle_mesh;
using testing::HasSubstr;

std::string ply_header(std::string_view format, std::string_view type, int vertices, int faces,
                       std::string_view index_type = "int") {
  return fmt::format("ply\nformat {} 1.0\nelement vertex {}\nproperty {} x\nproperty {} y\nproperty {} z\nelement "
                     "face {}\nproperty list uchar {} vertex_indices\nend_header\n",
                     format, vertices, type, type, type, faces, index_type);
}

template <class T>
void append(std::string& bytes, T value, bool big_endian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) bytes.push_back(raw[big_endian ? sizeof(T) - 1 - i : i]);
}

void expect_io_error(const std::function<void()>& read, const std::string& part) {
  try {
    read();
    ADD_FAILURE() << "no IoError; expected one containing: " << part;
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(part));
  }
}

TEST(PlyReader, IntegerAndUcharCoordinatesAreRead) {
  // The two PLY files that crashed CGAL's reader (SIGSEGV), now read with their values.
  const std::string ascii = ply_header("ascii", "int", 3, 1) + "0 0 0\n7 0 0\n0 -5 0\n3 0 1 2\n";
  const geometry::TriangleMesh a = parse_triangle_mesh(ascii, MeshFormat::Ply, "int.ply", 1e-3);
  ASSERT_EQ(a.vertices.size(), 3u);
  EXPECT_EQ(a.vertices[1], Eigen::Vector3d(7e-3, 0, 0));
  EXPECT_EQ(a.vertices[2], Eigen::Vector3d(0, -5e-3, 0));

  std::string binary = ply_header("binary_little_endian", "uchar", 3, 1, "uint");
  for (unsigned char v : {0, 0, 0, 200, 0, 0, 0, 255, 0}) binary.push_back(static_cast<char>(v));
  binary.push_back(3);
  for (std::uint32_t i : {0u, 1u, 2u}) append(binary, i, false);
  const geometry::TriangleMesh b = parse_triangle_mesh(binary, MeshFormat::Ply, "uchar.ply", 1.0);
  EXPECT_EQ(b.vertices[1].x(), 200.0);
  EXPECT_EQ(b.vertices[2].y(), 255.0);
  EXPECT_EQ(b.triangles[0], (std::array<int, 3>{0, 1, 2}));
}

TEST(PlyReader, BigEndianDoublesAndExtraPropertiesAndElements) {
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\ncomment made by hand\nelement vertex 3\nproperty double x\nproperty "
      "double y\nproperty double z\nproperty uchar red\nelement face 1\nproperty uchar flags\nproperty list uchar "
      "int vertex_index\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  const double xyz[3][3] = {{0.25, 0, 0}, {1, 0.5, 0}, {0, 1, -0.125}};
  for (const auto& p : xyz) {
    for (double c : p) append(bytes, c, true);
    bytes.push_back(9);  // red
  }
  bytes.push_back(1);  // flags
  bytes.push_back(3);
  for (std::int32_t i : {0, 1, 2}) append(bytes, i, true);
  for (std::int32_t i : {0, 1}) append(bytes, i, true);
  const geometry::TriangleMesh mesh = parse_triangle_mesh(bytes, MeshFormat::Ply, "be.ply", 1.0);
  ASSERT_EQ(mesh.vertices.size(), 3u);
  EXPECT_EQ(mesh.vertices[0], Eigen::Vector3d(0.25, 0, 0));
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(0, 1, -0.125));
  ASSERT_EQ(mesh.triangles.size(), 1u);
}

TEST(PlyReader, MalformedHeadersAndCountsAreRefusedBeforeAllocating) {
  // A property before any element crashed CGAL's reader (back() of an empty vector).
  expect_io_error([] {
    parse_triangle_mesh("ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\nend_header\n0\n", MeshFormat::Ply,
                        "p.ply", 1);
  }, "p.ply:3: PLY header: a property before any element");
  // Counts that the file's size cannot hold ended in std::bad_alloc.
  expect_io_error([] {
    parse_triangle_mesh(ply_header("binary_little_endian", "float", 2000000000, 2000000000) + "abcd", MeshFormat::Ply,
                        "big.ply", 1);
  }, "declares 2000000000 items");
  expect_io_error([] {
    parse_triangle_mesh(ply_header("ascii", "float", 3, 1, "int") + "0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n",
                        MeshFormat::Ply, "list.ply", 1);
  }, "a list of 255 entries is longer than the rest of the file");
  expect_io_error([] {
    parse_triangle_mesh(ply_header("ascii", "uchar", 3, 1) + "0 0 0\n1 0 0\n0 300 0\n3 0 1 2\n", MeshFormat::Ply,
                        "range.ply", 1);
  }, "'300' is not a uchar");
  expect_io_error([] { parse_triangle_mesh("ply\nformat ascii 1.0\nend_header\n", MeshFormat::Ply, "e.ply", 1); },
                  "0 vertices and 0 faces");
}

TEST(OffReader, ReadsVariantsAndRefusesHugeCounts) {
  const geometry::TriangleMesh mesh = parse_triangle_mesh(
      "# comment\nCOFF\n3 1 0\n0 0 0 255 0 0\n2 0 0 0 255 0\n0 2 0 0 0 255\n3 0 1 2 # a face\n", MeshFormat::Off,
      "c.off", 1.0);
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(2, 0, 0));
  const geometry::TriangleMesh homogeneous =
      parse_triangle_mesh("4OFF 3 1 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n3 0 1 2\n", MeshFormat::Off, "h.off", 1.0);
  EXPECT_EQ(homogeneous.vertices[1], Eigen::Vector3d(1, 0, 0));
  expect_io_error([] { parse_triangle_mesh("OFF\n2000000000 2000000000 0\n0 0 0\n", MeshFormat::Off, "x.off", 1); },
                  "x.off:2: OFF: the header declares 2000000000 vertices");
  expect_io_error([] {
    parse_triangle_mesh("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3000000000 0 1 2\n", MeshFormat::Off, "y.off", 1);
  }, "face 0 declares 3000000000 corners");
  expect_io_error([] { parse_triangle_mesh("OFF BINARY\n", MeshFormat::Off, "b.off", 1); }, "binary OFF");
}

TEST(SurfaceReaders, ADirectoryIsAnErrorNotAnEmptyMesh) {
  const auto directory = std::filesystem::temp_directory_path() / "needlekit-a-directory.stl";
  std::filesystem::create_directories(directory);
  expect_io_error([&] { geometry::read_triangle_mesh(directory, 1.0); }, "it is a directory");
  std::filesystem::remove(directory);
  expect_io_error([&] { geometry::read_triangle_mesh(directory, 1.0); }, "no such file");
}

TEST(BodySurface, AnInwardFacingClosedSurfaceIsTurnedOutwards) {
  geometry::TriangleMesh cube = test::cube_mesh(0.01);
  for (auto& t : cube.triangles) std::swap(t[1], t[2]);
  ASSERT_LT(geometry::signed_volume(cube), 0);
  const geometry::BodySurface body = geometry::body_surface(cube, "inward.obj");
  EXPECT_TRUE(body.flipped);
  EXPECT_THAT(body.note, HasSubstr("normals pointed inwards"));
  EXPECT_NEAR(geometry::signed_volume(body.surface.mesh()), 1e-6, 1e-18);
  // Outward normals: the bottom face's normal points down.
  const int bottom = body.surface.closest_point({0.005, 0.005, -0.001}).triangle;
  EXPECT_NEAR(body.surface.face_normal(bottom).z(), -1.0, 1e-12);
  EXPECT_FALSE(geometry::body_surface(test::cube_mesh(0.01), "outward.obj").flipped);
}

TEST(BodySurface, DegenerateTrianglesAreRefusedWithHowManyAndWhere) {
  // issue 16: a flat mesh with two zero-area triangles gave a flexible patch a strain of 1.09.
  geometry::TriangleMesh plane = test::plane_grid_mesh(0.01, 20);
  for (auto& v : plane.vertices) {
    if (std::abs(v.x() - 0.003) < 1e-9 && std::abs(v.y()) < 1e-9) v.x() = 0.002;  // one vertex onto its neighbour
  }
  const std::vector<int> degenerate = geometry::degenerate_triangles(plane);
  ASSERT_EQ(degenerate.size(), 2u);
  try {
    geometry::body_surface(plane, "flat.obj");
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), HasSubstr("flat.obj: not usable as a body surface: 2 of 800 triangles are degenerate"));
    EXPECT_THAT(e.what(), HasSubstr(fmt::format("triangle {} ", degenerate[0])));
    EXPECT_THAT(e.what(), HasSubstr(" mm"));
  }
}

}  // namespace
}  // namespace needlekit
