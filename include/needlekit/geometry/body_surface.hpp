// A body surface (dissertation §5.6) ready for patch fitting, from a triangle mesh: the manifold and orientation
// check must find nothing wrong, degenerate (zero-area) triangles are refused with how many there are and where,
// and a closed surface whose normals point inwards (negative enclosed volume) is turned outwards.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>

#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::geometry {

struct BodySurfaceOptions {
  bool weld = false;  // merge vertices of identical coordinates first (meshes exported with split seams)
};

struct BodySurface {
  SurfaceMesh surface;
  SurfaceCheck check;    // of the mesh as read (after welding, before turning)
  bool flipped = false;  // the closed surface faced inwards: every triangle was reversed
  std::string note;      // what was changed, for the user; empty when nothing was
};

// Throws InvalidInput naming `source_name` for a mesh that is non-manifold, inconsistently oriented or has
// degenerate triangles (their count and the first few, with their positions in mm).
BodySurface body_surface(TriangleMesh mesh, std::string_view source_name, const BodySurfaceOptions& options = {});

// read_triangle_mesh, then body_surface.
BodySurface read_body_surface(const std::filesystem::path& path, double unit_to_metre,
                              const BodySurfaceOptions& options = {});

}  // namespace needlekit::geometry
