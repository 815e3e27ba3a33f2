// Internal: the solver's function space on a tetrahedral tissue mesh — the nodes (the mesh's, plus one mid-edge node
// per edge for quadratic tetrahedra), the element connectivity, the shape-function gradients and quadrature weights
// at every quadrature point (computed once in the reference configuration: total-Lagrangian), the Lamé constants per
// element and an element colouring for lock-free threaded assembly (element_colouring.hpp).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "element_colouring.hpp"
#include "needlekit/fem/hyperelastic_law.hpp"
#include "needlekit/fem/solver_options.hpp"
#include "needlekit/mesh/tet_mesh.hpp"
#include "needlekit/mesh/coarse_level.hpp"

namespace needlekit::fem::detail {

struct FunctionSpace {
  int nodes_per_element = 4;                // 4 or 10
  int points = 1;                           // quadrature points per element (1 or 4)
  std::vector<Eigen::Vector3d> nodes;       // m, reference positions: the mesh's nodes, then the mid-edge nodes
  std::vector<std::vector<int>> elements;   // per element, VTK order (corners, then edges 01, 12, 20, 03, 13, 23)
  std::vector<int> connectivity;            // the same, flat, nodes_per_element per element
  std::vector<double> gradients;            // flat, points * 3 * nodes_per_element per element (column-major 3 x n)
  std::vector<double> weights;              // points per element: quadrature weight * det(J0), m^3
  std::vector<double> volumes;              // per element, reference volume, m^3
  // Per element F_r, the deformation gradient at zero displacement: I, except for a tetrahedron with its own
  // reference shape (mesh::OwnReference), whose gradients and volume are its own and F = F_r + u ∇N^T. Empty when
  // no element has one.
  std::vector<Eigen::Matrix3d> initial_gradient;
  Eigen::Matrix3d initial(size_t element) const {
    return initial_gradient.empty() ? Eigen::Matrix3d::Identity() : initial_gradient[element];
  }
  std::vector<LameConstants> lame;          // per element
  ElementColouring colouring;               // blocks of elements for threaded assembly (element_colouring.hpp)
  // The geometry the assembly reads per element, copied into its order (colouring.elements): it streams them front
  // to back instead of loading them from scattered elements (those loads' cache misses were half the assembly's
  // time). `lame` stays per element: the nodal average changes it after the space is built.
  struct AssemblyOrder {
    std::vector<int> connectivity;
    std::vector<double> gradients;
    std::vector<double> weights;
    std::vector<Eigen::Matrix3d> initial_gradient;  // empty when initial_gradient is
  } assembly;
  std::vector<double> node_youngs_modulus;  // per node, the stiffest adjacent layer's E, Pa
  mesh::CoarseLevel corners;                // quadratic: the corner nodes as the two-grid solver's coarse level
  Eigen::Vector3d box_min, box_max;         // m, bounding box of the mesh
  double mean_youngs_modulus = 0;           // Pa, volume-weighted
  double mean_element_size = 0;             // m, edge of the regular tetrahedron of the mean element volume
};

// Throws InvalidInput for an empty mesh, a layer index or node index out of range, E <= 0, nu outside (-1, 0.5),
// inverted or degenerate tetrahedra (naming the tetrahedron; for one with its own reference, its own edges), an own
// reference of a tetrahedron out of range or with quadratic elements.
void validate_tissue_mesh(const mesh::TetMesh& mesh);

// The function space of a valid mesh (validate_tissue_mesh first).
FunctionSpace function_space(const mesh::TetMesh& mesh, ElementOrder order);

}  // namespace needlekit::fem::detail
