#include "needlekit/mesh/uniform_refinement.hpp"

#include <algorithm>
#include <cstdint>

#include "needlekit/mesh/mesh_validation.hpp"

namespace needlekit::mesh {

UniformRefinement refine_uniformly(const TetMesh& coarse) {
  UniformRefinement out;
  TetMesh& fine = out.mesh;
  const int nc = static_cast<int>(coarse.nodes.size());
  const size_t ne = coarse.tets.size();
  fine.layers = coarse.layers;
  fine.nodes = coarse.nodes;
  out.coarse.nodes = nc;
  out.coarse.tets = coarse.tets;
  auto& parents = out.coarse.interpolation;
  parents.resize(static_cast<size_t>(nc));
  for (int a = 0; a < nc; ++a) parents[static_cast<size_t>(a)] = NodeInterpolation::at_node(a);

  // Edge numbering by sorting (key = smaller node * nc + larger node): deterministic, no hash map.
  static constexpr std::array<std::array<int, 2>, 6> kEdges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
  std::vector<std::pair<int64_t, int64_t>> keys;  // (edge key, tet * 6 + local edge)
  keys.reserve(ne * 6);
  for (size_t e = 0; e < ne; ++e)
    for (int k = 0; k < 6; ++k) {
      int a = coarse.tets[e][kEdges[k][0]], b = coarse.tets[e][kEdges[k][1]];
      if (a > b) std::swap(a, b);
      keys.emplace_back(static_cast<int64_t>(a) * nc + b, static_cast<int64_t>(e * 6 + k));
    }
  std::sort(keys.begin(), keys.end());
  std::vector<int> midpoint(ne * 6);
  int64_t previous = -1;
  for (const auto& [key, slot] : keys) {
    if (key != previous) {
      previous = key;
      const int a = static_cast<int>(key / nc), b = static_cast<int>(key % nc);
      fine.nodes.push_back(0.5 * (coarse.nodes[a] + coarse.nodes[b]));
      parents.push_back(NodeInterpolation::edge_midpoint(a, b));
    }
    midpoint[static_cast<size_t>(slot)] = static_cast<int>(fine.nodes.size()) - 1;
  }

  fine.tets.reserve(ne * 8);
  fine.tet_layer.reserve(ne * 8);
  for (size_t e = 0; e < ne; ++e) {
    const auto& t = coarse.tets[e];
    const int* m = &midpoint[e * 6];  // m[0..5] = midpoints of 01, 02, 03, 12, 13, 23
    const int m01 = m[0], m02 = m[1], m03 = m[2], m12 = m[3], m13 = m[4], m23 = m[5];
    // Corner tetrahedra: the parent scaled by 1/2 about each vertex (orientation kept).
    std::array<std::array<int, 4>, 8> children{{{t[0], m01, m02, m03},
                                                {m01, t[1], m12, m13},
                                                {m02, m12, t[2], m23},
                                                {m03, m13, m23, t[3]}}};
    // Inner octahedron: the shortest of its three diagonals, with the other four midpoints in cyclic order.
    const std::array<std::array<int, 6>, 3> octahedra{{{m01, m23, m02, m03, m13, m12},
                                                       {m02, m13, m01, m03, m23, m12},
                                                       {m03, m12, m01, m02, m23, m13}}};
    int best = 0;
    double shortest = 0;
    for (int d = 0; d < 3; ++d) {
      const double length = (fine.nodes[octahedra[d][0]] - fine.nodes[octahedra[d][1]]).squaredNorm();
      if (d == 0 || length < shortest) {
        best = d;
        shortest = length;
      }
    }
    const auto& o = octahedra[best];
    for (int k = 0; k < 4; ++k) children[4 + k] = {o[0], o[1], o[2 + k], o[2 + (k + 1) % 4]};
    for (auto& child : children) {
      const auto& p = fine.nodes;
      if (signed_volume(p[child[0]], p[child[1]], p[child[2]], p[child[3]]) < 0) std::swap(child[2], child[3]);
      fine.tets.push_back(child);
      fine.tet_layer.push_back(coarse.tet_layer[e]);
    }
  }
  return out;
}

}  // namespace needlekit::mesh
