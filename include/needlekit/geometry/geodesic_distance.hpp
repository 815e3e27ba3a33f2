// Geodesic distance between two points of a triangle surface by shooting straightest geodesics (Polthier & Schmies
// 1998) with Newton's method on the initial angle and the length.
//
// What is exact and what is not: a path found by shooting is straight in the unfolding of the triangles it crosses, so
// its length is the exact length of a locally shortest path on the polyhedral surface when it passes through no vertex
// (on convex surfaces such as a sphere shortest paths never touch a vertex; on a plane and on a polygonal cylinder the
// answer is exact to rounding). It is the globally shortest one when the two points are closer than the surface's cut
// locus (nearby points on a smooth surface: the use for patch springs); extra_shots and the graph fallback look for
// shorter ones but prove nothing. A converged path through a vertex whose total angle is below 2 pi (a cube's corner)
// is a geodesic but never a shortest path: the search then goes on with the other shots. Behind a saddle vertex (total
// angle > 2 pi) or a boundary vertex no straightest geodesic from the start arrives (they pass such a vertex with equal
// angles on both sides, shortest paths bend there); the saddle detour then takes the shortest path through one such
// vertex near the best shot, d(p, V) + d(V, q), which is exact when the true shortest path bends at exactly that one
// vertex. Paths that bend at two or more vertices are not found (status NotConverged); the exact polyhedral algorithm
// for the general case (Mitchell-Mount-Papadimitriou / Chen-Han) is not implemented.
#pragma once
#include <cstdint>
#include <string>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"

namespace needlekit::geometry {

struct GeodesicDistanceOptions {
  // Newton iterations per shot, [1, 1000].
  int max_iterations = 40;
  // Converged when the shot ends within this fraction of the straight-line distance (or within rounding of the
  // coordinates, whichever is larger), (0, 1e-3].
  double tolerance = 1e-11;
  // Additional shots from initial angles offset by +-0.3, +-0.6, ... rad from the direction towards the target,
  // [0, 20]. The shortest converged path is kept; 0 shoots once (and retries with offsets only on failure).
  int extra_shots = 0;
  // When no shot from the direction towards the target converges, restart from the direction and length of the
  // shortest path along mesh edges (Dijkstra; builds the vertex graph, O(triangles) per call).
  bool graph_fallback = true;
  // When still no shot converges, try paths that bend at one saddle or boundary vertex near the best shot and the
  // edge path (up to 64 such vertices, each costing two distance computations).
  bool saddle_detour = true;
  // The work budget: triangles crossed by all traced paths together (shots, fallback and detours), >= 1. When it is
  // spent the search stops with NotConverged and says so; a trace is also cut at the mesh's triangle count (a
  // shortest path crosses each triangle at most once). About 1e7 crossings per second.
  std::int64_t max_crossings = 50'000'000;
  TraceOptions trace;  // for each traced path
};

enum class DistanceStatus {
  Converged,     // a straightest geodesic from `from` ends at `to` within the tolerance
  NotConverged,  // no shot reached `to`; the best shot is kept
};
inline constexpr EnumTable<DistanceStatus, 2> kDistanceStatusNames{{
    {DistanceStatus::Converged, "converged", "a straightest geodesic from `from` ends at `to` within the tolerance"},
    {DistanceStatus::NotConverged, "not converged", "no shot reached `to`; the best shot is kept"},
}};
std::string_view to_string(DistanceStatus status);

struct GeodesicDistance {
  DistanceStatus status = DistanceStatus::NotConverged;
  std::string reason;     // empty when Converged
  double distance = 0;    // m, the length of `path` (the geodesic distance when Converged)
  double euclidean = 0;   // m, the straight-line distance |to - from|, a lower bound
  double miss = 0;        // m, how far the path's end lies from `to`
  int iterations = 0;     // Newton iterations over all shots
  double graph_distance = 0;  // m, the edge-path length when the graph fallback ran (an upper bound), else 0
  int via_vertex = -1;        // the saddle or boundary vertex the path bends at (saddle detour), else -1
  SurfacePath path;       // the path from `from` (towards `to`)
};

// The geodesic distance from `from` to `to` on `surface`. Throws InvalidInput for invalid locations.
GeodesicDistance geodesic_distance(const SurfaceMesh& surface, const SurfaceLocation& from, const SurfaceLocation& to,
                                   const GeodesicDistanceOptions& options = {});

}  // namespace needlekit::geometry
