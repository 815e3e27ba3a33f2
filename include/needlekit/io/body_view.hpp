// The 3D view of a body surface on its own (docs/views.md, kind "body"), before any patch is fitted on it: what
// `needlekit serve`'s patch tab draws so that the patch can be placed by a click. The whole surface, decimated by
// vertex clustering (geometry/vertex_clustering.hpp) when it has more than `max_triangles` triangles, with the index
// in the full mesh of every vertex drawn ("vertex_ids"), so that a picked point names a vertex of the mesh the fit
// reads.
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::io {

struct BodyViewOptions {
  int max_triangles = 12000;  // [1, inf): triangles drawn at most (12000: about 0.35 MB of view)
};

// {"format": "needlekit-view/1", "kind": "body", "name", "title", "steps": [one], "steps_total": 1, "surface":
// {"region": "whole body", "vertices", "triangles", "indices", "positions" (Float32, m), "normals" (Float32, the full
// mesh's unit vertex normals at the vertices drawn), "vertex_ids" (Uint32),
// "fields": []}, "full_mesh": {"vertices", "triangles"}, "cell_size_m", "notes"}. Throws InvalidInput for
// max_triangles < 1.
nlohmann::json body_view(const std::string& name, const geometry::SurfaceMesh& surface,
                         const BodyViewOptions& options = {});

// What a click on the body's view means on the full mesh (geometry/vertex_pick.hpp): {"hit": false} when the ray
// misses, else {"hit": true, "vertex" (its index in the mesh the fit reads), "triangle" (the one the ray met first),
// "position_m" (the vertex), "point_m" (where the ray met the surface), "normal" (the vertex's outward unit normal)}.
nlohmann::json body_pick(const geometry::SurfaceMesh& surface, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& direction);

}  // namespace needlekit::io
