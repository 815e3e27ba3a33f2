// Internal: the tissue block's boundary conditions (dissertation §3.4: sides and bottom fixed, top free, or the
// variants of BoundaryCondition), its top surface (contact candidates with their lumped areas), the nodes under a
// needle's flat tip (Eqs 3.9-3.12) and the resulting split of the degrees of freedom into free and prescribed ones.
#pragma once
#include <Eigen/Core>
#include <array>
#include <vector>

#include "function_space.hpp"
#include "needlekit/fem/solver_options.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::fem::detail {

// The nodes on the top surface z = z_top: the corners and (quadratic) mid-edge nodes of the boundary faces of the
// corner mesh (mesh::boundary_surface) lying in that plane.
struct TopSurface {
  double z = 0;                      // m, the top plane (the mesh's largest z)
  std::vector<int> nodes;            // ascending
  std::vector<double> node_area;     // per node of the function space: lumped area, m^2 (linear: A/3 per corner;
                                     // T6 faces: corners A/12, mid-edges A/4); 0 off the top
  std::vector<double> node_size;     // per node: smallest sqrt(2 A) of its top faces, m (inf off the top)
  // The top faces as linear triangles of function-space nodes, counter-clockwise seen from above (outward normal
  // +z in the reference state): the corner triangles, or for quadratic faces the four corner/mid-edge sub-triangles.
  std::vector<std::array<int, 3>> triangles;
};
// Throws InvalidInput when no boundary face lies on the top plane. `tolerance`: m, distance from the plane.
TopSurface top_surface(const mesh::TetMesh& mesh, const FunctionSpace& space, double tolerance);

// Per dof (3 * node + component): 1 when the boundary condition fixes it, on the faces of the bounding box within
// `tolerance` (m).
std::vector<char> fixed_dofs(const FunctionSpace& space, BoundaryCondition condition, double tolerance);

// The top nodes under a needle's flat tip (§3.4): those whose (x, y) lie in the needle's true outline at its lowest
// level — the downward-facing triangles there (within `tolerance` of that level) plus, over each boundary edge of
// that polygon, the circular segment up to the curve through its vertices — on the outline included; for a sharp tip
// the top node nearest the apex. The needle must point along -z.
std::vector<int> tip_nodes(const TopSurface& top, const FunctionSpace& space, const geometry::TriangleMesh& needle,
                           double tolerance);

// Free degrees of freedom: neither fixed nor prescribed by a needle tip, numbered node by node in `node_order`
// (every node once; the solver's is the Morton order of the nodes, morton_order.hpp: neighbouring nodes get nearby
// rows of the tangent).
struct DofMap {
  std::vector<int> free_index;  // per dof: index among the free dofs, or -1
  std::vector<int> free_dofs;   // per free index its dof (the inverse of free_index)
  std::vector<char> tip_dof;    // per dof: 1 when a needle tip prescribes it (z of a free tip node)
};
DofMap dof_map(const std::vector<char>& fixed, const std::vector<std::vector<int>>& tip_nodes_per_needle,
               const std::vector<int>& node_order);

}  // namespace needlekit::fem::detail
