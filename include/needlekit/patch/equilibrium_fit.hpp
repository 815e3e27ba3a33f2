// Beyond the dissertation: the patch's static equilibrium on the surface, a physically based alternative to node
// sweeping (Alg 5.1–5.3). Every node carries the insertion load f along the approach direction (§5.2: the input
// force points along −Z); the springs of Fig 5.6 (energy Eq 5.13) resist; the surface pushes back through
// frictionless contact, a penalty ½·κ·g² on the penetration g of each node. Frictionless contact leaves the patch
// free to slide down a slope and to twist; a tangential anchor (stiffness `anchor_ratio`·K per node, in the patch
// plane only) to the rigid fit's position — the applicator pad holding the patch laterally — removes those modes. The total potential
//   Π(x) = Σ_springs ½K(|x_a − x_b| − L0)² − Σ_nodes f·(a·x) + Σ_nodes ½κ·min(0, g(x))² + Σ_nodes ½·k_t·|P(x − x0)|²
// is minimised by Newton's method (springs' Hessians projected to be positive semi-definite, steps limited to a
// quarter pitch per node, backtracking line search; Eigen's sparse LDLᵀ).
#pragma once
#include <functional>

#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/patch/fitted_patch.hpp"

namespace needlekit::patch {

struct EquilibriumFitOptions {
  double node_load = 0.0712;     // N, (0, inf): force pressing each node along the approach (default: F(A) of a
                                 // 70 µm tip, the force that punctures one needle, Eq 4.2)
  double contact_ratio = 1e3;    // (0, inf): contact penalty κ = contact_ratio · max spring constant
  double anchor_ratio = 1;       // [0, inf): tangential anchor stiffness per node = anchor_ratio · max spring constant
                                 // (the applicator pad holding the patch laterally; 0 leaves it free to slide)
  double tolerance = 1e-5;       // (0, 1): stop when |∇Π|∞ < tolerance · node_load
  int max_iterations = 500;      // [1, 100000]; each Newton step moves a node by at most a quarter pitch
  // Called after each Newton iteration k with the larger of k / max_iterations and the decades of the gradient reduced,
  // log(|g0|/|g|) / log(|g0|/tol) of |grad|inf, in [0, 1] and never decreasing (1 when converged). Return false to
  // stop: equilibrium_fit throws needlekit::Interrupted. May be empty.
  std::function<bool(double)> progress;
};

// Starts from the rigid fit. Status NotConverged (with the last iterate) when the iteration limit is reached;
// MissesSurface / BoundaryReached as the rigid fit. Throws InvalidInput for out-of-range options.
FittedPatch equilibrium_fit(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                            const EquilibriumFitOptions& options = {});

// The total potential Π of a configuration (for tests: finite differences, energy decrease).
double equilibrium_potential(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                             const std::vector<Eigen::Vector3d>& anchor, const std::vector<Eigen::Vector3d>& positions,
                             const EquilibriumFitOptions& options);

}  // namespace needlekit::patch
