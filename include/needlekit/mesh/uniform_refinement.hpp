// Uniform ("red") refinement of a tetrahedral mesh: every tetrahedron split into eight (Bey 1995, "Tetrahedral grid
// refinement", Computing 55: four corner tetrahedra, and the inner octahedron cut along its shortest diagonal so
// that the children's shapes stay within a fixed bound of the parent's). The result remembers where each node came
// from: the coarse mesh and this parentage are the coarse level of the FE solver's two-grid preconditioner
// (fem::CoarseLevel), so a block meshed at twice the element size and split once solves faster than one meshed at
// the final size directly.
#pragma once
#include <array>
#include <vector>

#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

// A coarse mesh seen from a finer one whose nodes interpolate it linearly: fine nodes 0 .. nodes - 1 are the coarse
// nodes, every other fine node lies at the midpoint of a coarse edge.
struct CoarseLevel {
  int nodes = 0;                                 // coarse nodes
  std::vector<std::array<int, 4>> tets;          // coarse tetrahedra (coarse node indices)
  // Per fine node, the coarse nodes it interpolates: {a, a} for a coarse node, {a, b} for the midpoint of edge ab.
  std::vector<std::array<int, 2>> node_parents;
};

struct UniformRefinement {
  TetMesh mesh;         // the fine mesh; children keep their parent's layer
  CoarseLevel coarse;   // the mesh it was split from
};

// Splits every tetrahedron of `coarse` into eight. The children are right-handed when the parent is.
UniformRefinement refine_uniformly(const TetMesh& coarse);

}  // namespace needlekit::mesh
