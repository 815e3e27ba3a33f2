// A closed, outward-oriented triangle surface mesh of a needle (cylinder, cone, bevel; solid or hollow), in the
// needle frame of needle_geometry.hpp (axis z, base at z = 0, tip at z = L). Later capabilities use it for FE
// contact and post-puncture forces.
#pragma once
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::needle {

struct NeedleMeshOptions {
  int circumferential_segments = 64;  // around the axis, >= 8
  int axial_segments = 16;            // along the length, >= 1 (the bevel face uses this too)
};

// The mesh: side wall, base disk (annulus for hollow needles), tip face (disk, segment or annulus), bore wall for
// hollow needles, and for bevels the elliptic bevel face. Its enclosed volume converges to volume(needle) as the
// segments increase (second order in 1/segments).
geometry::TriangleMesh needle_surface_mesh(const NeedleGeometry& needle, const NeedleMeshOptions& options = {});

}  // namespace needlekit::needle
