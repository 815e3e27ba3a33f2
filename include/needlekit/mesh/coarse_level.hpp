// The coarse level of the FE solver's two-grid preconditioner (src/fem/two_grid_preconditioner.hpp): a coarser
// tetrahedral mesh of the same body and, per node of the fine mesh, the coarse nodes whose linear shape functions
// interpolate it. Nested levels (a split mesh's parent, refine_uniformly; the corner nodes of quadratic
// tetrahedra) put a fine node on a coarse node or an edge midpoint. A non-nested level (the same body meshed again
// at three times the sizes, LayeredBlockOptions::coarse_size_factor) gives each fine node the barycentric coordinates
// of the coarse tetrahedron that contains it: interpolating_coarse_level.
#pragma once
#include <array>
#include <vector>

#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

// One fine node as a combination of up to four coarse nodes: weights >= 0 that sum to 1; unused slots hold node -1
// and weight 0.
struct NodeInterpolation {
  std::array<int, 4> nodes{-1, -1, -1, -1};
  std::array<double, 4> weights{0, 0, 0, 0};

  static NodeInterpolation at_node(int a) { return {{a, -1, -1, -1}, {1, 0, 0, 0}}; }
  static NodeInterpolation edge_midpoint(int a, int b) { return {{a, b, -1, -1}, {0.5, 0.5, 0, 0}}; }
};

struct CoarseLevel {
  int nodes = 0;                                 // coarse nodes
  std::vector<std::array<int, 4>> tets;          // coarse tetrahedra (coarse node indices)
  std::vector<NodeInterpolation> interpolation;  // per fine node
};

// The coarse level of `fine` on `coarse`, an independent mesh of the same body: each fine node takes the
// barycentric coordinates of the coarse tetrahedron that contains it (found through a Boost.Geometry R-tree of the
// tetrahedra's bounding boxes). A node on a face or an edge may lie in several; one of them is taken. A node outside
// every coarse tetrahedron (a boundary node of a curved body, or rounding) takes the tetrahedron it is least outside
// of, its coordinates clipped at zero and rescaled to sum to 1: the interpolation is then no longer exact for linear
// fields there, which costs the preconditioner a little and the solution nothing. Throws InvalidInput for an empty
// coarse mesh.
CoarseLevel interpolating_coarse_level(const TetMesh& fine, const TetMesh& coarse);

}  // namespace needlekit::mesh
