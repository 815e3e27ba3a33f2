// Internal: the placement of a tilted needle (IndentationCase::angle, azimuth) and the loads the tissue puts on it
// beyond the axial force: the lateral force across its axis, the moment about its base, and the ch. 4 bending check
// of the lateral load (insertion/indentation.hpp, "Angled insertion").
#pragma once
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"

namespace needlekit::insertion::detail {

// The rotation that takes the needle from tip-down (axis −z, a bevel's face towards +x) to the case's angle and
// azimuth: the tilt by θ about (sin φ, −cos φ, 0) after the turn by φ about z. Exactly the identity at θ = φ = 0.
Eigen::Matrix3d needle_rotation(const IndentationCase& indentation_case);

// m: the needle's travel along its axis from the start to first touching the undeformed surface, for a tip at
// `tip_height` above it (tip_height / cos θ).
double travel_to_surface(const IndentationCase& indentation_case, double tip_height);

// The tissue's loads on the needles of a converged step: the force across each needle's axis and the moment about
// each needle's base centre (`bases`: m, one per needle as placed at zero displacement), summed over the needles.
struct NeedleLoads {
  Eigen::Vector3d lateral_force = Eigen::Vector3d::Zero();  // N
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();         // N m
};
NeedleLoads needle_loads(const fem::StepResult& solved, const Eigen::Vector3d& axis,
                         const std::vector<Eigen::Vector3d>& bases);

// The bending check on the last step's lateral load: empty without a parametric needle, a material with an allowable
// stress, or a step.
std::optional<BendingCheck> bending_check(const IndentationCase& indentation_case,
                                          const std::vector<IndentationStep>& steps);

}  // namespace needlekit::insertion::detail
