// Geodesic distance between two points of a triangle surface by shooting straightest geodesics (Polthier & Schmies
// 1998) with Newton's method on the initial angle and the length.
//
// What is exact and what is not: a path found here is straight in the unfolding of the triangles it crosses, so its
// length is the exact length of a locally shortest path on the polyhedral surface whenever it passes through no
// vertex (always so when it converges beside the vertices, e.g. on convex surfaces such as a sphere, where shortest
// paths never touch a vertex; on a plane and on a polygonal cylinder the answer is exact to rounding). It is the
// globally shortest one when the two points are closer than the surface's cut locus (nearby points on a smooth
// surface, the use for patch springs). It is an upper bound, not the exact shortest distance, when the true shortest
// path must bend around a saddle vertex (total angle > 2 pi): straightest paths pass saddle vertices with equal
// angles on both sides, shortest ones with at least pi on each. The exact polyhedral algorithm for that case
// (Mitchell-Mount-Papadimitriou / Chen-Han) is not implemented.
#pragma once
#include <string>

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
  TraceOptions trace;  // for each traced path
};

enum class DistanceStatus {
  Converged,     // a straightest geodesic from `from` ends at `to` within the tolerance
  NotConverged,  // no shot reached `to`; the best shot is kept
};
const char* to_string(DistanceStatus status);

struct GeodesicDistance {
  DistanceStatus status = DistanceStatus::NotConverged;
  std::string reason;     // empty when Converged
  double distance = 0;    // m, the length of `path` (the geodesic distance when Converged)
  double euclidean = 0;   // m, the straight-line distance |to - from|, a lower bound
  double miss = 0;        // m, how far the path's end lies from `to`
  int iterations = 0;     // Newton iterations over all shots
  SurfacePath path;       // the path from `from` (towards `to`)
};

// The geodesic distance from `from` to `to` on `surface`. Throws InvalidInput for invalid locations.
GeodesicDistance geodesic_distance(const SurfaceMesh& surface, const SurfaceLocation& from, const SurfaceLocation& to,
                                   const GeodesicDistanceOptions& options = {});

}  // namespace needlekit::geometry
