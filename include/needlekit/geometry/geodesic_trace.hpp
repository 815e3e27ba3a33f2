// Straightest geodesics on a triangle surface (Polthier & Schmies 1998, "Straightest geodesics on polyhedral
// surfaces"): from a surface point, walk straight within a triangle; at an edge, unfold the next triangle about the
// shared edge (the direction keeps its angle to the edge); at a vertex, leave so that the angles on both sides are
// equal (half the vertex's total angle). On a developable surface (plane, cylinder) this is the exact geodesic.
// The dissertation's geodesic traverse (Algorithm 5.3) follows a cutting plane instead: cutting_plane_trace.hpp.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::geometry {

// A point on the surface: a triangle and barycentric coordinates in it (non-negative, summing to one).
struct SurfaceLocation {
  int triangle = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3);
};
inline SurfaceLocation surface_location(const ClosestPoint& point) { return {point.triangle, point.barycentric}; }
// The location of a mesh vertex (e.g. a suggested patch centre). Throws InvalidInput for an index out of range or a
// vertex that no triangle uses.
SurfaceLocation vertex_location(const SurfaceMesh& surface, int vertex);
// The position of a location in space (m).
Eigen::Vector3d position(const SurfaceMesh& surface, const SurfaceLocation& location);

enum class PathStatus {
  Completed,           // the full length was travelled
  HitBoundary,         // the path reached the surface boundary (an open edge or a boundary vertex) first
  DegenerateTriangle,  // the next triangle has (nearly) no area, so no direction can be carried across it
  StepLimit,           // more triangles than TraceOptions::max_steps, or no progress at a vertex
};
inline constexpr EnumTable<PathStatus, 4> kPathStatusNames{{
    {PathStatus::Completed, "completed", "the full length was travelled"},
    {PathStatus::HitBoundary, "hit boundary", "the path reached the surface boundary first"},
    {PathStatus::DegenerateTriangle, "degenerate triangle", "the next triangle has (nearly) no area"},
    {PathStatus::StepLimit, "step limit", "more triangles than max_steps, or no progress at a vertex"},
}};
std::string_view to_string(PathStatus status);

struct TraceOptions {
  // Triangles a path may cross, [1, inf). Guards against endless walks; a 10 mm path on the 1.5 mm neck mesh
  // crosses ~10-20.
  int max_steps = 1'000'000;
  // Barycentric tolerance, [0, 1e-3]: an edge crossing closer than this fraction of the edge to one of its ends
  // passes through that vertex (the vertex rule applies instead of the edge rule).
  double vertex_tolerance = 1e-10;
  // A triangle is degenerate when twice its area is below this fraction of its longest edge squared (a smallest
  // angle below ~this many radians), [0, 1e-3].
  double degenerate_sine = 1e-10;
};

// A vertex the path passed through (where the walk's vertex rule chose how to go on).
struct VertexCrossing {
  int vertex = -1;
  double total_angle = 0;  // rad, the sum of the triangle angles around the vertex (2 pi where it is flat)
};

// The result of walking on the surface. Everything travelled so far is kept when the walk ends early.
struct SurfacePath {
  PathStatus status = PathStatus::Completed;
  std::string reason;                  // empty when Completed
  SurfaceLocation end;                 // where the path stops
  Eigen::Vector3d end_point = Eigen::Vector3d::Zero();      // m, position(end)
  Eigen::Vector3d end_direction = Eigen::Vector3d::Zero();  // unit, in the end triangle's plane
  double length = 0;                   // m travelled along the surface (the requested length when Completed)
  std::vector<Eigen::Vector3d> points; // m: the start, every edge or vertex crossing, the end
  std::vector<int> triangles;          // the triangle of each segment points[i] -> points[i+1]
  std::vector<VertexCrossing> vertex_crossings;  // vertices passed through on the way, in order
};

// The straightest geodesic from `start` with initial direction `direction` (any length; projected onto the start
// triangle's plane) for arc length `length` (m, >= 0). A start on an edge leaves into the triangle the direction points
// into; a start at a vertex uses the polar map: a direction within the start triangle's corner keeps its angle, the
// directions outside it are spread proportionally over the other triangles around the vertex (so that all of a saddle
// vertex's surroundings, more than 2 pi, can be reached). Throws InvalidInput for an invalid location, a negative or
// non-finite length, or a direction normal to the surface.
SurfacePath straightest_geodesic(const SurfaceMesh& surface, const SurfaceLocation& start,
                                 const Eigen::Vector3d& direction, double length, const TraceOptions& options = {});

}  // namespace needlekit::geometry
