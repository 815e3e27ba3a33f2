#include "needlekit/patch/rigid_fit.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <cmath>
#include <limits>

namespace needlekit::patch {

FittedPatch rigid_fit(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame) {
  FittedPatch fit;
  fit.frame = frame;
  const std::vector<Eigen::Vector3d> start = flat_positions(design, frame, frame.approach_height);
  double contact = std::numeric_limits<double>::infinity();
  std::vector<double> hit_distance(design.node_count(), std::numeric_limits<double>::infinity());
  for (int k = 0; k < design.node_count(); ++k) {
    if (const auto hit = surface.first_hit(start[k], frame.approach)) {
      hit_distance[k] = hit->distance;
      if (hit->distance < contact) {
        contact = hit->distance;
        fit.first_node = k;
      }
    } else {
      fit.affected_nodes.push_back(k);
    }
  }
  // The substrate is a plate: a surface vertex under its footprint may touch before any node does.
  const Eigen::Vector3d origin = frame.surface_point - frame.approach_height * frame.approach;
  double plate_contact = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& vertex : surface.mesh().vertices) {
    const Eigen::Vector3d r = vertex - origin;
    const double along = r.dot(frame.approach);
    if (along > 0 && along < plate_contact && std::abs(r.dot(frame.u)) <= 0.5 * design.width_u &&
        std::abs(r.dot(frame.v)) <= 0.5 * design.width_v) {
      plate_contact = along;
    }
  }
  if (fit.first_node >= 0) contact = std::min(contact, plate_contact);
  fit.normals.assign(design.node_count(), -frame.approach);
  fit.on_surface.assign(design.node_count(), false);
  if (fit.first_node < 0) {
    fit.positions = start;
    fit.status = FitStatus::MissesSurface;
    fit.reason = "no node of the patch lies over the surface along the approach direction";
    return fit;
  }
  fit.positions.resize(design.node_count());
  const double tolerance = 1e-9 * (design.width_u + design.width_v);
  for (int k = 0; k < design.node_count(); ++k) {
    fit.positions[k] = start[k] + contact * frame.approach;
    fit.on_surface[k] = hit_distance[k] - contact <= tolerance;
  }
  if (!fit.affected_nodes.empty()) {
    fit.status = FitStatus::BoundaryReached;
    fit.reason = fmt::format("{} node(s) hang over the surface's edge (no surface under them): nodes {}",
                             fit.affected_nodes.size(), fmt::join(fit.affected_nodes, ", "));
  }
  return fit;
}

}  // namespace needlekit::patch
