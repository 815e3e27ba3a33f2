#include "needlekit/patch/patch_placement.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::patch {

std::string_view to_string(Approach approach) { return name_of(kApproachNames, approach); }

PatchFrame patch_frame(const geometry::SurfaceMesh& surface, const Placement& placement, double patch_diagonal,
                       double needle_length) {
  PatchFrame frame;
  Eigen::Vector3d normal;
  if (placement.center_vertex) {
    const int vertex = *placement.center_vertex;
    if (vertex < 0 || vertex >= surface.vertex_count()) {
      throw InvalidInput(fmt::format("surface.center_vertex: {} does not exist, expected a vertex index in [0, {}]",
                                     vertex, surface.vertex_count() - 1));
    }
    frame.surface_point = surface.mesh().vertices[vertex];
    frame.triangle = surface.closest_point(frame.surface_point).triangle;
    normal = surface.vertex_normal(vertex);
  } else {
    if (!placement.center.allFinite()) throw InvalidInput("surface.center: not a finite point");
    const geometry::ClosestPoint closest = surface.closest_point(placement.center);
    if (closest.distance > placement.max_center_distance) {
      throw InvalidInput(fmt::format(
          "surface.center: ({:.6g}, {:.6g}, {:.6g}) mm is {:.6g} mm from the surface, expected a point within {:.6g} mm "
          "of it (the patch centre must lie on the mesh)",
          placement.center.x() * 1e3, placement.center.y() * 1e3, placement.center.z() * 1e3, closest.distance * 1e3,
          placement.max_center_distance * 1e3));
    }
    frame.surface_point = closest.point;
    frame.triangle = closest.triangle;
    normal = surface.interpolated_normal(closest.triangle, closest.barycentric);
  }
  frame.approach = placement.approach == Approach::MinusZ ? Eigen::Vector3d(0, 0, -1) : Eigen::Vector3d(-normal);
  if (normal.dot(frame.approach) >= 0) {
    throw InvalidInput(fmt::format(
        "surface.approach: the surface at the patch centre faces away from the approach direction ({}; surface normal "
        "({:.3g}, {:.3g}, {:.3g})), expected a centre on a side of the surface that the patch can reach",
        to_string(placement.approach), normal.x(), normal.y(), normal.z()));
  }
  // U: the X axis (Y when approaching along X) projected onto the patch plane, then turned by `rotation`.
  const Eigen::Vector3d& a = frame.approach;
  Eigen::Vector3d reference = std::abs(a.x()) > 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  Eigen::Vector3d u = (reference - reference.dot(a) * a).normalized();
  u = Eigen::AngleAxisd(placement.rotation, -a) * u;  // right-handed about the patch normal −a
  frame.u = u;
  frame.v = (-a).cross(u);
  frame.approach_height = placement.approach_height > 0 ? placement.approach_height : patch_diagonal + needle_length;
  return frame;
}

}  // namespace needlekit::patch
