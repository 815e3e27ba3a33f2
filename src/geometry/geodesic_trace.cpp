#include "needlekit/geometry/geodesic_trace.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "needlekit/core/errors.hpp"
#include "surface_walk.hpp"

namespace needlekit::geometry {
namespace {

using detail::DirectionIn;
using detail::Fan;

// Polthier & Schmies (1998): across an edge the path unfolds; through a vertex it leaves at half the vertex's total
// angle from where it came in (equal angles on both sides), which on a flat vertex (total angle 2 pi) is straight.
class StraightestRule final : public detail::WalkRule {
public:
  Eigen::Vector3d across_edge(const SurfaceMesh& surface, int from, int edge, int next,
                              const Eigen::Vector3d& d) const override {
    return detail::unfolded_direction(surface, from, edge, next, d);
  }

  std::optional<DirectionIn> through_vertex(const SurfaceMesh& surface, const Fan& fan, int arrival,
                                            const Eigen::Vector3d& d, std::string& reason) const override {
    const auto& in = fan.wedges[arrival];
    if (!fan.closed) {
      reason = fmt::format("reached the boundary vertex {}", surface.mesh().triangles[in.triangle][in.corner]);
      return std::nullopt;
    }
    // The reversed incoming direction lies in the arrival wedge; the outgoing one is half the total angle away.
    const double back = std::clamp(detail::angle_in_wedge(surface, in.triangle, in.corner, -d), 0.0, in.angle);
    const auto out = detail::wedge_at(fan, fan.angle_before(arrival) + back + 0.5 * fan.total_angle);
    if (!out) {
      reason =
          fmt::format("the triangles around vertex {} have no angle", surface.mesh().triangles[in.triangle][in.corner]);
      return std::nullopt;
    }
    const auto& wedge = fan.wedges[out->first];
    return DirectionIn{wedge.triangle, detail::direction_in_wedge(surface, wedge, out->second)};
  }

  std::optional<DirectionIn> leave_vertex(const SurfaceMesh& surface, const Fan& fan, int start,
                                          const Eigen::Vector3d& d, std::string& reason) const override {
    // The polar map at a vertex: a direction inside the start wedge keeps its angle; the directions outside it
    // (2 pi - theta of them) are spread proportionally over the rest of a closed fan (total angle - theta), so that
    // every wedge of a saddle or cone vertex is reachable. An open fan is continued unscaled.
    const auto& in = fan.wedges[start];
    double angle = detail::angle_in_wedge(surface, in.triangle, in.corner, d);
    if (fan.closed && (angle < 0 || angle > in.angle)) {
      const double outside = (angle < 0 ? angle + 2 * std::numbers::pi : angle) - in.angle;
      angle = in.angle + outside * (fan.total_angle - in.angle) / (2 * std::numbers::pi - in.angle);
    }
    const auto out = detail::wedge_at(fan, fan.angle_before(start) + angle);
    if (!out) {
      reason = fmt::format("the direction points off the surface at the boundary vertex {}",
                           surface.mesh().triangles[in.triangle][in.corner]);
      return std::nullopt;
    }
    const auto& wedge = fan.wedges[out->first];
    return DirectionIn{wedge.triangle, detail::direction_in_wedge(surface, wedge, out->second)};
  }
};

}  // namespace

SurfacePath straightest_geodesic(const SurfaceMesh& surface, const SurfaceLocation& start,
                                 const Eigen::Vector3d& direction, double length, const TraceOptions& options) {
  const SurfaceLocation from = detail::checked_location(surface, start, "straightest_geodesic");
  if (!std::isfinite(length) || length < 0) {
    throw InvalidInput(fmt::format("straightest_geodesic: length {} m must be finite and >= 0", length));
  }
  const Eigen::Vector3d& n = surface.face_normal(from.triangle);
  const Eigen::Vector3d tangent = direction - direction.dot(n) * n;
  if (!direction.allFinite() || !(tangent.norm() > 1e-12 * direction.norm())) {
    throw InvalidInput(fmt::format("straightest_geodesic: direction ({}, {}, {}) has no component along the surface "
                                   "at triangle {}", direction.x(), direction.y(), direction.z(), from.triangle));
  }
  return detail::walk(surface, from, tangent.normalized(), length, StraightestRule{}, options);
}

}  // namespace needlekit::geometry
