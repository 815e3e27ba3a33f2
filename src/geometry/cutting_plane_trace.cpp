#include "needlekit/geometry/cutting_plane_trace.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "surface_walk.hpp"

namespace needlekit::geometry {
namespace {

using detail::DirectionIn;
using detail::Fan;

// Algorithm 5.3: the path follows the plane with unit normal `plane_normal` through the start point.
class CuttingPlaneRule final : public detail::WalkRule {
public:
  explicit CuttingPlaneRule(const Eigen::Vector3d& plane_normal) : m_(plane_normal) {}

  Eigen::Vector3d across_edge(const SurfaceMesh& surface, int from, int edge, int next,
                              const Eigen::Vector3d& d) const override {
    const Eigen::Vector3d& n = surface.face_normal(next);
    const Eigen::Vector3d line = n.cross(m_);
    // A triangle lying in the cutting plane has no section line: carry the direction on by unfolding.
    if (!(line.norm() > 1e-12)) return detail::unfolded_direction(surface, from, edge, next, d);
    // The section line through the crossing point enters `next` in one sense and `from` in the other: take the
    // sense that increases the barycentric coordinate of next's corner opposite the shared edge.
    const auto& tn = surface.mesh().triangles[next];
    const auto& tf = surface.mesh().triangles[from];
    int opposite = 0;
    while (tn[opposite] == tf[edge] || tn[opposite] == tf[(edge + 1) % 3]) ++opposite;
    const auto& v = surface.mesh().vertices;
    const Eigen::Vector3d inward = n.cross(v[tn[(opposite + 2) % 3]] - v[tn[(opposite + 1) % 3]]).normalized();
    const Eigen::Vector3d unit = line.normalized();
    const double into = unit.dot(inward);
    if (std::abs(into) > 1e-12) return into > 0 ? unit : Eigen::Vector3d(-unit);
    return unit.dot(d) >= 0 ? unit : Eigen::Vector3d(-unit);  // the plane holds the edge: keep going forward
  }

  std::optional<DirectionIn> through_vertex(const SurfaceMesh& surface, const Fan& fan, int arrival,
                                            const Eigen::Vector3d& d, std::string& reason) const override {
    return most_straight(surface, fan, arrival, d, reason);
  }

  std::optional<DirectionIn> leave_vertex(const SurfaceMesh& surface, const Fan& fan, int /*start*/,
                                          const Eigen::Vector3d& d, std::string& reason) const override {
    return most_straight(surface, fan, -1, d, reason);
  }

private:
  // Of the section's rays from the vertex into each wedge, the one most nearly along d, other than the ray back
  // along which the path arrived (in wedge `arrival`).
  std::optional<DirectionIn> most_straight(const SurfaceMesh& surface, const Fan& fan, int arrival,
                                           const Eigen::Vector3d& d, std::string& reason) const {
    std::optional<DirectionIn> best;
    double best_score = -2;
    for (std::size_t i = 0; i < fan.wedges.size(); ++i) {
      const auto& wedge = fan.wedges[i];
      const Eigen::Vector3d line = surface.face_normal(wedge.triangle).cross(m_);
      if (!(line.norm() > 1e-12)) continue;
      for (double sign : {1.0, -1.0}) {
        const Eigen::Vector3d ray = sign * line.normalized();
        const double angle = detail::angle_in_wedge(surface, wedge.triangle, wedge.corner, ray);
        const double slack = 1e-9 * wedge.angle;
        if (angle < -slack || angle > wedge.angle + slack) continue;
        if (static_cast<int>(i) == arrival && ray.dot(d) < -1 + 1e-9) continue;  // the way back
        if (ray.dot(d) > best_score) {
          best_score = ray.dot(d);
          best = DirectionIn{wedge.triangle, detail::direction_in_wedge(surface, wedge, angle)};
        }
      }
    }
    if (!best) {
      const auto& w = fan.wedges.front();
      reason = fmt::format("the cutting plane meets no triangle around vertex {} beyond the path",
                           surface.mesh().triangles[w.triangle][w.corner]);
    }
    return best;
  }

  Eigen::Vector3d m_;
};

}  // namespace

SurfacePath cutting_plane_trace(const SurfaceMesh& surface, const SurfaceLocation& start,
                                const Eigen::Vector3d& direction, double length, const TraceOptions& options) {
  const SurfaceLocation from = detail::checked_location(surface, start, "cutting_plane_trace");
  if (!std::isfinite(length) || length < 0) {
    throw InvalidInput(fmt::format("cutting_plane_trace: length {} m must be finite and >= 0", length));
  }
  // The plane through the start spanned by d and the surface normal there (notes on Algorithm 5.3).
  const Eigen::Vector3d normal = surface.interpolated_normal(from.triangle, from.barycentric);
  const Eigen::Vector3d plane_normal = direction.cross(normal);
  if (!direction.allFinite() || !(plane_normal.norm() > 1e-12 * direction.norm())) {
    throw InvalidInput(fmt::format("cutting_plane_trace: direction ({}, {}, {}) is along the surface normal at "
                                   "triangle {}: it spans no cutting plane", direction.x(), direction.y(),
                                   direction.z(), from.triangle));
  }
  const CuttingPlaneRule rule(plane_normal.normalized());
  // In the start triangle the path runs along the section line, in the sense of d.
  const Eigen::Vector3d line = surface.face_normal(from.triangle).cross(plane_normal.normalized());
  Eigen::Vector3d initial = line.norm() > 1e-12 ? Eigen::Vector3d(line.normalized()) : direction.normalized();
  if (initial.dot(direction) < 0) initial = -initial;
  return detail::walk(surface, from, initial, length, rule, options);
}

}  // namespace needlekit::geometry
