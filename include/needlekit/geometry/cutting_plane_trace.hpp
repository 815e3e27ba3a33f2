// The dissertation's geodesic traverse (Algorithm 5.3, §5.7.3): travel a given length along the curve where a
// cutting plane meets the surface, crossing adjacent triangles. The plane passes through the start point and is
// spanned by the moving direction d and the surface normal there (the notes' reading of "a cutting plane which d
// is on"). On a sphere this curve is a great circle and on a plane a straight line; in general it is a normal
// section, not a geodesic (straightest_geodesic gives the geodesic).
#pragma once
#include <Eigen/Core>

#include "needlekit/geometry/geodesic_trace.hpp"

namespace needlekit::geometry {

// Walks `length` (m, >= 0) from `start` along the intersection of the surface with the plane through the start
// point spanned by `direction` and the interpolated surface normal at the start (SurfaceMesh::interpolated_normal),
// leaving in the sense of `direction`. At a vertex the curve continues into the triangle where the plane's section
// continues most nearly straight. Stops cleanly (status + reason) at the boundary or a degenerate triangle.
// Throws InvalidInput for an invalid location, a negative or non-finite length, or a direction along the normal.
SurfacePath cutting_plane_trace(const SurfaceMesh& surface, const SurfaceLocation& start,
                                const Eigen::Vector3d& direction, double length, const TraceOptions& options = {});

}  // namespace needlekit::geometry
