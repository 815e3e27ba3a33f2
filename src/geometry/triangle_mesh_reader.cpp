// read_triangle_mesh: OBJ, PLY and OFF through CGAL's polygon-soup readers, STL through needlekit's read_stl (which
// merges identical vertices). Faces are never triangulated: a face with more or fewer than three corners is refused.
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <vector>

#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::geometry {
namespace {

using Point = CGAL::Simple_cartesian<double>::Point_3;

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

TriangleMesh from_soup(const std::filesystem::path& path, std::string_view format, const std::vector<Point>& points,
                       const std::vector<std::vector<std::size_t>>& polygons, double unit_to_metre) {
  if (points.empty() || polygons.empty()) {
    throw IoError(fmt::format("{}: the {} file holds {} vertices and {} faces; expected a triangle mesh",
                              path.string(), format, points.size(), polygons.size()));
  }
  std::size_t non_triangles = 0, first_non_triangle = 0, first_size = 0;
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    if (polygons[f].size() != 3) {
      if (non_triangles++ == 0) first_non_triangle = f, first_size = polygons[f].size();
    }
  }
  if (non_triangles > 0) {
    throw IoError(fmt::format("{}: {} of {} faces are not triangles (face {} has {} corners); needlekit reads "
                              "triangle meshes only: triangulate it first",
                              path.string(), non_triangles, polygons.size(), first_non_triangle + 1, first_size));
  }
  TriangleMesh mesh;
  mesh.vertices.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p(points[i].x(), points[i].y(), points[i].z());
    if (!p.allFinite()) throw IoError(fmt::format("{}: vertex {} is not finite", path.string(), i + 1));
    mesh.vertices.push_back(unit_to_metre * p);
  }
  mesh.triangles.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      const std::size_t index = polygons[f][c];
      if (index >= points.size()) {
        throw IoError(fmt::format("{}: face {} refers to vertex {} (1-based), but the file has {} vertices",
                                  path.string(), f + 1, static_cast<long long>(index) + 1, points.size()));
      }
      t[c] = static_cast<int>(index);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

}  // namespace

TriangleMesh read_triangle_mesh(const std::filesystem::path& path, double unit_to_metre) {
  if (!std::isfinite(unit_to_metre) || unit_to_metre <= 0) {
    throw InvalidInput(fmt::format("read_triangle_mesh({}): unit {} m must be a positive finite length",
                                   path.string(), unit_to_metre));
  }
  const std::string ext = lower_extension(path);
  if (ext == ".stl") return read_stl(path, unit_to_metre);
  if (ext != ".obj" && ext != ".ply" && ext != ".off") {
    throw IoError(fmt::format("{}: unknown mesh format '{}'; expected .obj, .stl, .ply or .off", path.string(), ext));
  }
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw IoError(fmt::format("{}: cannot open the mesh file for reading", path.string()));
  }
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  std::string format;
  // The library never prints: CGAL's PLY reader is verbose unless told otherwise.
  const auto quiet = CGAL::parameters::verbose(false);
  if (ext == ".obj") {
    format = "OBJ";
    ok = CGAL::IO::read_OBJ(path.string(), points, polygons, quiet);
  } else if (ext == ".off") {
    format = "OFF";
    ok = CGAL::IO::read_OFF(path.string(), points, polygons, quiet);
  } else {
    format = "PLY";
    ok = CGAL::IO::read_PLY(path.string(), points, polygons, quiet);
  }
  if (!ok) {
    throw IoError(fmt::format("{}: CGAL's {} reader could not parse the file (read {} vertices and {} faces before "
                              "stopping); expected a valid {} triangle mesh",
                              path.string(), format, points.size(), polygons.size(), format));
  }
  return from_soup(path, format, points, polygons, unit_to_metre);
}

}  // namespace needlekit::geometry
