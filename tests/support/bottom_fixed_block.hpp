// A small structured block of linear tetrahedra with its bottom face fixed, as the internal fem pieces (pattern,
// product) take it: the flat connectivity and the per-dof fixed flags.
#pragma once
#include <algorithm>
#include <vector>

#include "needlekit/mesh/structured_block_mesh.hpp"

namespace needlekit::test {

struct BottomFixedBlock {
  mesh::TetMesh mesh;
  std::vector<int> connectivity;  // 4 node indices per tetrahedron
  std::vector<char> fixed;        // per dof (3 * node + component): 1 on the bottom face
};

inline BottomFixedBlock bottom_fixed_block(int nx, int ny, int nz) {
  mesh::StructuredBlockOptions o;
  o.width = o.length = 1e-3, o.height = 0.5e-3;
  o.nx = nx, o.ny = ny, o.nz = nz;
  BottomFixedBlock b;
  b.mesh = mesh::structured_block_mesh(o);
  for (const auto& t : b.mesh.tets) b.connectivity.insert(b.connectivity.end(), t.begin(), t.end());
  double bottom = 0;
  for (const auto& x : b.mesh.nodes) bottom = std::min(bottom, x.z());
  b.fixed.assign(3 * b.mesh.nodes.size(), 0);
  for (size_t n = 0; n < b.mesh.nodes.size(); ++n)
    if (b.mesh.nodes[n].z() < bottom + 1e-9) b.fixed[3 * n] = b.fixed[3 * n + 1] = b.fixed[3 * n + 2] = 1;
  return b;
}

}  // namespace needlekit::test
