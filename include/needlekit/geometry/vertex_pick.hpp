// The vertex of a surface that a click on its picture means: the first triangle the click's ray meets (the camera's
// ray through the clicked pixel, in the mesh's coordinates), and the corner of that triangle nearest to where the ray
// meets it. Only the hit triangle's corners are candidates, so a vertex on the far side of a thin part (nearer in
// space, hidden from the camera) is never picked. `needlekit serve` resolves a click on a decimated body view
// (geometry/vertex_clustering.hpp) to the full mesh with it.
#pragma once
#include <Eigen/Core>
#include <optional>

#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::geometry {

struct VertexPick {
  int vertex = -1;        // index in the surface's mesh
  int triangle = -1;      // the triangle the ray met first
  Eigen::Vector3d point;  // m, where the ray met it
};

// Empty when the ray misses the surface. Throws InvalidInput for a non-finite origin or a zero direction.
std::optional<VertexPick> pick_vertex(const SurfaceMesh& surface, const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction);

}  // namespace needlekit::geometry
