#include "needlekit/geometry/vertex_clustering.hpp"

#include <Eigen/Geometry>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

#include "needlekit/core/errors.hpp"

namespace needlekit::geometry {
namespace {

// The vertices that triangles use, in index order.
std::vector<int> used_vertices(const TriangleMesh& mesh) {
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const auto& t : mesh.triangles) {
    for (const int k : t) used[static_cast<std::size_t>(k)] = true;
  }
  std::vector<int> vertices;
  for (std::size_t k = 0; k < used.size(); ++k) {
    if (used[k]) vertices.push_back(static_cast<int>(k));
  }
  return vertices;
}

// The mesh restricted to `kept` triangles, its vertices renumbered in order of first use.
ClusteredMesh compacted(const TriangleMesh& mesh, const std::vector<std::array<int, 3>>& kept, double cell_size) {
  ClusteredMesh result;
  result.cell_size = cell_size;
  std::unordered_map<int, int> renumbered;
  for (const auto& t : kept) {
    std::array<int, 3> out{};
    for (int c = 0; c < 3; ++c) {
      const auto [it, added] = renumbered.try_emplace(t[c], static_cast<int>(result.source_vertex.size()));
      if (added) {
        result.source_vertex.push_back(t[c]);
        result.mesh.vertices.push_back(mesh.vertices[static_cast<std::size_t>(t[c])]);
      }
      out[c] = it->second;
    }
    result.mesh.triangles.push_back(out);
  }
  return result;
}

// One clustering pass on cells of edge `h` from `origin`: the kept triangles, in the input's vertex numbers.
std::vector<std::array<int, 3>> clustered_triangles(const TriangleMesh& mesh, const std::vector<int>& vertices,
                                                    const Eigen::Vector3d& origin, double h) {
  const auto cell_of = [&](int k) {
    const Eigen::Vector3d x = (mesh.vertices[static_cast<std::size_t>(k)] - origin) / h;
    const auto axis = [](double v) { return static_cast<std::uint64_t>(std::max(0.0, std::floor(v))) & 0x1fffff; };
    return axis(x.x()) | axis(x.y()) << 21 | axis(x.z()) << 42;  // 21 bits per axis
  };
  std::unordered_map<std::uint64_t, std::pair<Eigen::Vector3d, int>> mean;  // cell -> (sum, count)
  for (const int k : vertices) {
    auto& [sum, count] = mean.try_emplace(cell_of(k), Eigen::Vector3d::Zero(), 0).first->second;
    sum += mesh.vertices[static_cast<std::size_t>(k)];
    ++count;
  }
  std::unordered_map<std::uint64_t, std::pair<int, double>> representative;  // cell -> (vertex, distance to mean)
  for (const int k : vertices) {
    const std::uint64_t cell = cell_of(k);
    const auto& [sum, count] = mean.at(cell);
    const double d = (mesh.vertices[static_cast<std::size_t>(k)] - sum / count).norm();
    const auto [it, added] = representative.try_emplace(cell, k, d);
    if (!added && d < it->second.second) it->second = {k, d};
  }
  const auto normal = [&](const std::array<int, 3>& c) {  // area-weighted
    const auto& v = mesh.vertices;
    const Eigen::Vector3d& a = v[static_cast<std::size_t>(c[0])];
    return Eigen::Vector3d((v[static_cast<std::size_t>(c[1])] - a).cross(v[static_cast<std::size_t>(c[2])] - a));
  };
  std::vector<std::array<int, 3>> kept;
  std::vector<Eigen::Vector3d> facing;         // per kept triangle: the summed normals of the triangles it stands for
  std::map<std::array<int, 3>, std::size_t> index_of;  // sorted corners of a kept triangle -> its index
  for (const auto& t : mesh.triangles) {
    const std::array<int, 3> r{representative.at(cell_of(t[0])).first, representative.at(cell_of(t[1])).first,
                               representative.at(cell_of(t[2])).first};
    if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2]) continue;
    std::array<int, 3> key = r;
    std::sort(key.begin(), key.end());
    const auto [it, added] = index_of.try_emplace(key, kept.size());
    if (added) {
      kept.push_back(r);
      facing.push_back(Eigen::Vector3d::Zero());
    }
    facing[it->second] += normal(t);
  }
  // Moving the corners to their cells' representatives can fold a thin triangle over: each kept triangle faces the
  // way the surface it stands for faces (a viewer lights a triangle seen from behind as the surface's dark back).
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (normal(kept[k]).dot(facing[k]) < 0) std::swap(kept[k][1], kept[k][2]);
  }
  return kept;
}

}  // namespace

ClusteredMesh clustered_mesh(const TriangleMesh& mesh, int max_triangles) {
  if (max_triangles < 1) {
    throw InvalidInput(fmt::format("max_triangles: {} is out of range, expected an integer >= 1", max_triangles));
  }
  if (mesh.triangles.size() <= static_cast<std::size_t>(max_triangles)) return compacted(mesh, mesh.triangles, 0);
  const std::vector<int> vertices = used_vertices(mesh);
  Eigen::Vector3d lo = mesh.vertices[static_cast<std::size_t>(vertices.front())], hi = lo;
  for (const int k : vertices) {
    lo = lo.cwiseMin(mesh.vertices[static_cast<std::size_t>(k)]);
    hi = hi.cwiseMax(mesh.vertices[static_cast<std::size_t>(k)]);
  }
  // A closed surface clustered on cells of edge h keeps about two triangles per cell it crosses, and crosses about
  // area / h^2 of them: start where that is max_triangles.
  const double diagonal = (hi - lo).norm();
  double h = std::max(std::sqrt(2 * surface_area(mesh) / max_triangles), 1e-6 * diagonal);
  for (;; h *= 1.25) {
    std::vector<std::array<int, 3>> kept = clustered_triangles(mesh, vertices, lo, h);
    if (kept.size() <= static_cast<std::size_t>(max_triangles)) return compacted(mesh, kept, h);
  }
}

}  // namespace needlekit::geometry
