#include "needlekit/mesh/tet_adjacency.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <tuple>
#include <unordered_set>

#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/mesh_validation.hpp"

namespace needlekit::mesh {
namespace {

struct FaceRecord {
  std::array<int, 3> key;  // sorted node indices
  int tet;
  int local;
};

std::array<int, 3> sorted(std::array<int, 3> a) {
  std::sort(a.begin(), a.end());
  return a;
}

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

TetTopology tet_topology(const TetMesh& mesh) {
  const std::size_t n = mesh.tets.size();
  std::vector<FaceRecord> faces;
  faces.reserve(4 * n);
  for (std::size_t e = 0; e < n; ++e) {
    for (int f = 0; f < 4; ++f) {
      const auto& t = mesh.tets[e];
      faces.push_back({sorted({t[kTetFaces[f][0]], t[kTetFaces[f][1]], t[kTetFaces[f][2]]}), static_cast<int>(e), f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const FaceRecord& a, const FaceRecord& b) {
    return std::tie(a.key, a.tet, a.local) < std::tie(b.key, b.tet, b.local);
  });
  TetTopology top;
  top.tet_triangles.assign(n, {-1, -1, -1, -1});
  top.tet_neighbors.assign(n, {-1, -1, -1, -1});
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) {
      throw InvalidInput(fmt::format("mesh: the face ({}, {}, {}) is shared by {} tetrahedra ({}, {}, {}, ...); "
                                     "expected at most two (a conforming, non-overlapping mesh)",
                                     faces[i].key[0], faces[i].key[1], faces[i].key[2], j - i, faces[i].tet,
                                     faces[i + 1].tet, faces[i + 2].tet));
    }
    const int triangle = static_cast<int>(top.triangles.size());
    const auto& t = mesh.tets[faces[i].tet];
    const auto& lf = kTetFaces[faces[i].local];
    top.triangles.push_back({t[lf[0]], t[lf[1]], t[lf[2]]});
    top.tet_triangles[faces[i].tet][faces[i].local] = triangle;
    if (j - i == 2) {
      const FaceRecord& a = faces[i];
      const FaceRecord& b = faces[i + 1];
      top.tet_triangles[b.tet][b.local] = triangle;
      top.tet_neighbors[a.tet][a.local] = b.tet;
      top.tet_neighbors[b.tet][b.local] = a.tet;
      top.triangle_tets.push_back({a.tet, b.tet});
    } else {
      top.triangle_tets.push_back({faces[i].tet, -1});
      top.boundary_triangles.push_back(triangle);
    }
    i = j;
  }
  return top;
}

BoundarySurface boundary_surface(const TetMesh& mesh, const TetTopology& topology) {
  BoundarySurface s;
  for (int triangle : topology.boundary_triangles) {
    const int e = topology.triangle_tets[triangle][0];
    const auto& t = mesh.tets[e];
    int local = 0;
    while (topology.tet_triangles[e][local] != triangle) ++local;
    const auto& lf = kTetFaces[local];
    std::array<int, 3> tri{t[lf[0]], t[lf[1]], t[lf[2]]};
    const int opposite = t[6 - lf[0] - lf[1] - lf[2]];  // local indices sum to 6
    // The normal of (a, b, c) points towards the opposite node when the signed volume is positive: flip it out.
    if (signed_volume(mesh.nodes[tri[0]], mesh.nodes[tri[1]], mesh.nodes[tri[2]], mesh.nodes[opposite]) > 0) {
      std::swap(tri[1], tri[2]);
    }
    s.triangles.push_back(tri);
    s.tets.push_back(e);
  }
  // Triangle-triangle adjacency through edges shared by exactly two boundary triangles.
  struct EdgeRecord {
    std::uint64_t key;
    int triangle;
    int local;
  };
  std::vector<EdgeRecord> edges;
  edges.reserve(3 * s.triangles.size());
  for (std::size_t f = 0; f < s.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      edges.push_back({edge_key(s.triangles[f][k], s.triangles[f][(k + 1) % 3]), static_cast<int>(f), k});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const EdgeRecord& a, const EdgeRecord& b) { return std::tie(a.key, a.triangle) < std::tie(b.key, b.triangle); });
  s.neighbors.assign(s.triangles.size(), {-1, -1, -1});
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i == 2) {
      s.neighbors[edges[i].triangle][edges[i].local] = edges[i + 1].triangle;
      s.neighbors[edges[i + 1].triangle][edges[i + 1].local] = edges[i].triangle;
    }
    i = j;
  }
  return s;
}

int euler_characteristic(const BoundarySurface& surface) {
  std::unordered_set<int> vertices;
  std::unordered_set<std::uint64_t> edges;
  for (const auto& t : surface.triangles) {
    for (int k = 0; k < 3; ++k) {
      vertices.insert(t[k]);
      edges.insert(edge_key(t[k], t[(k + 1) % 3]));
    }
  }
  return static_cast<int>(vertices.size()) - static_cast<int>(edges.size()) + static_cast<int>(surface.triangles.size());
}

}  // namespace needlekit::mesh
