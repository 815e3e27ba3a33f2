// Uniform ("red") refinement of a tetrahedral mesh: every tetrahedron split into eight (Bey 1995, "Tetrahedral grid
// refinement", Computing 55: four corner tetrahedra, and the inner octahedron cut along its shortest diagonal so
// that the children's shapes stay within a fixed bound of the parent's). The result remembers where each node came
// from: the coarse mesh and this parentage are the coarse level of the FE solver's two-grid preconditioner
// (mesh::CoarseLevel), so a block meshed at twice the element size and split once solves faster than one meshed at
// the final size directly.
#pragma once
#include "needlekit/mesh/coarse_level.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

struct UniformRefinement {
  TetMesh mesh;         // the fine mesh; children keep their parent's layer
  CoarseLevel coarse;   // the mesh it was split from: fine nodes 0 .. coarse.nodes - 1 are its nodes, every other
                        // fine node the midpoint of one of its edges
};

// Splits every tetrahedron of `coarse` into eight. The children are right-handed when the parent is.
UniformRefinement refine_uniformly(const TetMesh& coarse);

}  // namespace needlekit::mesh
