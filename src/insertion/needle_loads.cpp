#include "needle_loads.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "needlekit/analysis/bending.hpp"

namespace needlekit::insertion::detail {

Eigen::Matrix3d needle_rotation(const IndentationCase& c) {
  if (c.angle == 0 && c.azimuth == 0) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d tilt_axis(std::sin(c.azimuth), -std::cos(c.azimuth), 0.0);
  return (Eigen::AngleAxisd(c.angle, tilt_axis) * Eigen::AngleAxisd(c.azimuth, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

double travel_to_surface(const IndentationCase& c, double tip_height) { return tip_height / std::cos(c.angle); }

NeedleLoads needle_loads(const fem::StepResult& solved, const Eigen::Vector3d& axis,
                         const std::vector<Eigen::Vector3d>& bases) {
  NeedleLoads loads;
  for (std::size_t k = 0; k < solved.contact_force.size() && k < bases.size(); ++k) {
    const Eigen::Vector3d& force = solved.contact_force[k];
    loads.lateral_force += force - force.dot(axis) * axis;
    // The moment about the base: the solver's is about the needle's point at the origin (quasi_static_solver.hpp).
    if (k < solved.contact_moment.size()) loads.moment += solved.contact_moment[k] - bases[k].cross(force);
  }
  return loads;
}

std::optional<BendingCheck> bending_check(const IndentationCase& c, const std::vector<IndentationStep>& steps) {
  if (!c.geometry || !c.material || !c.material->allowable_stress || steps.empty()) return std::nullopt;
  BendingCheck check;
  check.lateral_load = steps.back().lateral_force.norm();
  // Eqs 5.7/5.8: the cantilever loaded across its axis at the tip.
  check.critical_load = analysis::critical_bending_load(*c.geometry, *c.material->allowable_stress);
  check.margin = check.lateral_load > 0 ? check.critical_load / check.lateral_load
                                        : std::numeric_limits<double>::infinity();
  return check;
}

}  // namespace needlekit::insertion::detail
