#include "coulomb_friction.hpp"

#include <cmath>

namespace needlekit::fem::detail {

FrictionResponse friction_response(const FrictionState& state, const Eigen::Vector3d& q, double stiffness) {
  FrictionResponse out;
  if (state.bound <= 0) return out;
  const Eigen::Matrix3d tangential = Eigen::Matrix3d::Identity() - state.normal * state.normal.transpose();
  // Trial force t_n + k_t s, s the slip in the frozen tangent plane (the header's law).
  const Eigen::Vector3d trial = tangential * (state.traction + stiffness * (q - state.reference));
  const double magnitude = trial.norm();
  if (magnitude <= state.bound) {  // stick
    out.energy = magnitude * magnitude / (2 * stiffness);
    out.force = trial;
    out.stiffness = stiffness * tangential;
    return out;
  }
  // Slip: the return mapping onto the cone |t| = mu p and its exact derivative at the frozen bound.
  const Eigen::Vector3d direction = trial / magnitude;
  out.slipping = true;
  out.energy = state.bound * magnitude / stiffness - state.bound * state.bound / (2 * stiffness);
  out.force = state.bound * direction;
  out.stiffness = state.bound * stiffness / magnitude * (tangential - direction * direction.transpose());
  return out;
}

}  // namespace needlekit::fem::detail
