// Total-Lagrangian tetrahedral elements (dissertation §3.4): linear (4 nodes, Eq 3.6's B matrix) and quadratic
// (10 nodes, VTK order: corners, then mid-points of edges 01, 12, 20, 03, 13, 23) with a 4-point Gauss rule.
// Internal force f = ∫ B(u)^T S dV (Eq 3.8: K u + g(u) u) and its consistent tangent (material + geometric).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "needlekit/fem/hyperelastic_law.hpp"

namespace needlekit::fem {

// Reference shape-function gradients and weights at the quadrature points of one element, precomputed once.
struct ElementGeometry {
  int nodes = 4;                                  // 4 or 10
  std::vector<Eigen::Matrix<double, 3, Eigen::Dynamic>> gradients;  // per quadrature point: dN/dX, 3 x nodes
  std::vector<double> weights;                    // per quadrature point: w * det(J0) (reference volume share)
  double volume = 0;                              // m^3, reference
};

// Throws nothing; `volume` <= 0 signals an inverted or degenerate element (the caller validates).
ElementGeometry element_geometry(const std::vector<Eigen::Vector3d>& reference_nodes);

struct ElementResponse {
  double energy = 0;             // J, ∫ W dV
  Eigen::VectorXd force;         // N, internal force, 3 * nodes (x, y, z per node)
  Eigen::MatrixXd tangent;       // N/m, d force / d u, (3 * nodes)^2, symmetric
  bool valid = true;             // false when an inverted quadrature point was met (neo-Hookean)
};

// Energy, internal force and (if asked) consistent tangent for nodal displacements u (3 * nodes).
ElementResponse element_response(const ElementGeometry& geometry, MaterialLaw law, const LameConstants& lame,
                                 const Eigen::VectorXd& displacement, bool with_tangent = true);

}  // namespace needlekit::fem
