#include "needlekit/geometry/vertex_pick.hpp"

namespace needlekit::geometry {

std::optional<VertexPick> pick_vertex(const SurfaceMesh& surface, const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) {
  const std::optional<RayHit> hit = surface.first_hit(origin, direction);
  if (!hit) return std::nullopt;
  const TriangleMesh& mesh = surface.mesh();
  const auto& corners = mesh.triangles[static_cast<std::size_t>(hit->triangle)];
  VertexPick pick{corners[0], hit->triangle, hit->point};
  for (const int corner : corners) {
    if ((mesh.vertices[static_cast<std::size_t>(corner)] - hit->point).squaredNorm() <
        (mesh.vertices[static_cast<std::size_t>(pick.vertex)] - hit->point).squaredNorm()) {
      pick.vertex = corner;
    }
  }
  return pick;
}

}  // namespace needlekit::geometry
