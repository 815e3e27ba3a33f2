// What the surface targets run on a mesh their reader accepted: the manifold/orientation check and, when that finds
// nothing wrong, the SurfaceMesh index (adjacency, normals, AABB tree) with one closest-point query.
#pragma once
#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::fuzz {

inline void check_surface(geometry::TriangleMesh mesh) {
  const geometry::SurfaceCheck check = geometry::surface_check(mesh);
  if (!check.problems.empty()) return;
  const geometry::SurfaceMesh surface(std::move(mesh));
  (void)surface.closest_point(Eigen::Vector3d::Zero());
}

}  // namespace needlekit::fuzz
