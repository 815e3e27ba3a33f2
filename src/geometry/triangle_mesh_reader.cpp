// read_triangle_mesh: OBJ through CGAL's polygon-soup reader, PLY and OFF through needlekit's (ply_reader.cpp and
// off_reader.cpp say why), STL through read_stl (which merges identical vertices). Faces are never triangulated: a
// face with more or fewer than three corners is refused.
#include <CGAL/IO/OBJ.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <string>
#include <vector>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/file_bytes.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "polygon_soup.hpp"

namespace needlekit::geometry {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

detail::PolygonSoup read_obj_soup(std::string_view bytes, std::string_view source_name) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::istringstream in{std::string(bytes)};
  // The library never prints: CGAL's readers are verbose unless told otherwise.
  if (!CGAL::IO::read_OBJ(in, points, polygons, CGAL::parameters::verbose(false))) {
    throw IoError(fmt::format("{}: CGAL's OBJ reader could not parse the file (read {} vertices and {} faces before "
                              "stopping); expected a valid OBJ triangle mesh",
                              source_name, points.size(), polygons.size()));
  }
  detail::PolygonSoup soup;
  soup.points.reserve(points.size());
  for (const Point& p : points) soup.points.emplace_back(p.x(), p.y(), p.z());
  soup.polygons.reserve(polygons.size());
  for (const auto& polygon : polygons) soup.polygons.emplace_back(polygon.begin(), polygon.end());
  return soup;
}

TriangleMesh from_soup(std::string_view source_name, std::string_view format, const detail::PolygonSoup& soup,
                       double unit_to_metre) {
  const auto& points = soup.points;
  const auto& polygons = soup.polygons;
  if (points.empty() || polygons.empty()) {
    throw IoError(fmt::format("{}: the {} file holds {} vertices and {} faces; expected a triangle mesh",
                              source_name, format, points.size(), polygons.size()));
  }
  if (points.size() >= (std::size_t{1} << 31)) {
    throw IoError(fmt::format("{}: {} vertices, more than a needlekit mesh can index (2^31 - 1)", source_name,
                              points.size()));
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
                              source_name, non_triangles, polygons.size(), first_non_triangle + 1, first_size));
  }
  TriangleMesh mesh;
  mesh.vertices.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = unit_to_metre * points[i];
    if (!p.allFinite()) throw IoError(fmt::format("{}: vertex {} is not finite", source_name, i + 1));
    mesh.vertices.push_back(p);
  }
  mesh.triangles.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      const std::int64_t index = polygons[f][c];
      if (index < 0 || static_cast<std::uint64_t>(index) >= points.size()) {
        throw IoError(fmt::format("{}: face {} refers to vertex {} (1-based), but the file has {} vertices",
                                  source_name, f + 1, index + (index < 0 ? 0 : 1), points.size()));
      }
      t[c] = static_cast<int>(index);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

}  // namespace

std::string_view to_string(MeshFormat format) { return name_of(kMeshFormatNames, format); }

TriangleMesh parse_triangle_mesh(std::string_view bytes, MeshFormat format, std::string_view source_name,
                                 double unit_to_metre) {
  if (!std::isfinite(unit_to_metre) || unit_to_metre <= 0) {
    throw InvalidInput(fmt::format("read_triangle_mesh({}): unit {} m must be a positive finite length", source_name,
                                   unit_to_metre));
  }
  switch (format) {
    case MeshFormat::Stl: return parse_stl(bytes, source_name, unit_to_metre);
    case MeshFormat::Obj:
      return from_soup(source_name, to_string(format), read_obj_soup(bytes, source_name), unit_to_metre);
    case MeshFormat::Ply:
      return from_soup(source_name, to_string(format), detail::read_ply_soup(bytes, source_name), unit_to_metre);
    case MeshFormat::Off:
      return from_soup(source_name, to_string(format), detail::read_off_soup(bytes, source_name), unit_to_metre);
  }
  throw InvalidInput(fmt::format("{}: unknown mesh format {}", source_name, static_cast<int>(format)));
}

TriangleMesh read_triangle_mesh(const std::filesystem::path& path, double unit_to_metre) {
  if (!std::isfinite(unit_to_metre) || unit_to_metre <= 0) {
    throw InvalidInput(fmt::format("read_triangle_mesh({}): unit {} m must be a positive finite length",
                                   path.string(), unit_to_metre));
  }
  const std::string ext = lower_extension(path);
  MeshFormat format;
  if (ext == ".obj") format = MeshFormat::Obj;
  else if (ext == ".stl") format = MeshFormat::Stl;
  else if (ext == ".ply") format = MeshFormat::Ply;
  else if (ext == ".off") format = MeshFormat::Off;
  else throw IoError(fmt::format("{}: unknown mesh format '{}'; expected .obj, .stl, .ply or .off", path.string(), ext));
  const std::string bytes = read_file_bytes(path, fmt::format("{} mesh file", to_string(format)));
  return parse_triangle_mesh(bytes, format, path.string(), unit_to_metre);
}

}  // namespace needlekit::geometry
