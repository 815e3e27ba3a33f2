// Internal: regularised Coulomb friction of a tissue node sliding on a rigid needle (surface contact), one node at a
// time. Stick is a tangential penalty spring k_t on the slip since the last converged load step; slip caps the
// tangential force at the friction bound mu * p by a return mapping (Simo & Laursen, Comput. Struct. 42, 1992, §3;
// Wriggers, Computational Contact Mechanics, 2nd ed. 2006, ch. 5, the regularised Coulomb law):
//   t_trial = t_n + k_t s,   t = t_trial                       if |t_trial| <= mu p   (stick)
//                            t = mu p t_trial / |t_trial|      otherwise              (slip)
// with t_n the tangential force of the last converged step and s the tangential slip since then.
//
// Within one Newton solve the friction bound mu p and the tangent plane (its normal) are frozen at their values of
// the last augmented-Lagrangian update, like the normal multipliers: the friction force is then the gradient of the
// convex potential
//   phi(s) = |t_trial|^2 / (2 k_t)                              (stick)
//          = mu p |t_trial| / k_t - (mu p)^2 / (2 k_t)          (slip)
// so the tangent is symmetric and exact (the symmetric CG/Cholesky solvers and the energy line search apply as they
// are), and the augmentations iterate the bound to the converged normal force: a sequence of Tresca problems
// converging to Coulomb's (the fixed point of Panagiotopoulos, Ing. Arch. 44, 1975). docs/fem_solver.md argues
// the choice against the non-symmetric consistent tangent of the unfrozen law.
#pragma once
#include <Eigen/Core>

namespace needlekit::fem::detail {

// Relative change of the friction bound (largest |mu p - bound| over the largest mu p) below which the
// augmentations take the bound as converged.
inline constexpr double kFrictionBoundTolerance = 1e-3;

// The frozen state of one node's friction.
struct FrictionState {
  double bound = 0;                                       // N, mu p of the last update; 0: no friction
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();      // unit: the tangent plane's normal at the last update
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();    // m, the node in the needle's frame at the last converged step
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();     // N, the tangential force t_n of the last converged step
};

struct FrictionResponse {
  double energy = 0;                                      // J, phi
  Eigen::Vector3d force = Eigen::Vector3d::Zero();        // N, t = d phi / dq: on the needle; the node gets -t
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();    // N/m, d^2 phi / dq^2 (symmetric)
  bool slipping = false;
};

// The response at the node's position q (m, in the needle's frame) for the tangential stiffness k_t (N/m, > 0).
FrictionResponse friction_response(const FrictionState& state, const Eigen::Vector3d& q, double stiffness);

}  // namespace needlekit::fem::detail
