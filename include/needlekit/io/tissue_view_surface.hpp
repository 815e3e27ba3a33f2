// The tissue's surface for the report's 3D views (docs/views.md): the boundary faces of the tetrahedral mesh (faces
// with one tetrahedron, mesh/tet_adjacency.hpp) on their own compact vertex list, and the per-vertex values of one
// load step: deformed position, displacement magnitude, von Mises stress and contact pressure.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::io {

struct TissueViewSurface {
  std::vector<int> nodes;                               // the mesh node of each surface vertex, ascending
  std::vector<std::array<std::uint32_t, 3>> triangles;  // into `nodes`, normals pointing out of the tissue
};

// Every boundary face: a closed surface (Euler characteristic 2 for a block). Throws InvalidInput for a
// non-manifold mesh (as mesh::tet_topology).
TissueViewSurface tissue_view_surface(const mesh::TetMesh& tissue);

// The faces of `surface` on the top surface z = 0 of the tissue (the frame of tet_mesh.hpp; within 1e-9 of the
// mesh's size), where the needles are: the view's decimation when the whole boundary is too large.
TissueViewSurface top_surface(const TissueViewSurface& surface, const mesh::TetMesh& tissue);

// Volume-weighted average at each mesh node of a value per tetrahedron (e.g. the solver's per-element von Mises
// stress): sum over the node's tetrahedra of |V_e| v_e / sum |V_e|; 0 at a node of no tetrahedron. Throws
// InvalidInput when `element_values` does not have one value per tetrahedron.
std::vector<double> nodal_average(const mesh::TetMesh& tissue, std::span<const double> element_values);

// One load step on the surface, per vertex of TissueViewSurface::nodes.
struct SurfaceStep {
  std::vector<float> positions;          // m, x y z of the deformed vertex
  std::vector<float> displacement;       // m, |u|
  std::vector<float> von_mises_stress;   // Pa, nodal average of the element values
  std::vector<float> contact_pressure;   // Pa
};

// `displacement` and `contact_pressure` are per FE node (the mesh's nodes come first, as fem::QuasiStaticSolver
// numbers them), `von_mises_stress` per tetrahedron. Throws InvalidInput for arrays shorter than the mesh needs.
SurfaceStep surface_step(const TissueViewSurface& surface, const mesh::TetMesh& tissue,
                         std::span<const Eigen::Vector3d> displacement, std::span<const double> contact_pressure,
                         std::span<const double> von_mises_stress);

}  // namespace needlekit::io
