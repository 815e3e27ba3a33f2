#include "needlekit/geometry/geodesic_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "needlekit/core/errors.hpp"
#include "surface_walk.hpp"

namespace needlekit::geometry {

const char* to_string(DistanceStatus status) {
  switch (status) {
    case DistanceStatus::Converged: return "converged";
    case DistanceStatus::NotConverged: return "not converged";
  }
  return "unknown";
}

namespace {

// Largest Newton step in the angle (rad): keeps a shot from jumping to another sheet of geodesics.
constexpr double kMaxAngleStep = 0.5;
// Shots without improvement after which a shot is abandoned.
constexpr int kStall = 6;

struct Shot {
  bool converged = false;
  double miss = std::numeric_limits<double>::infinity();
  SurfacePath path;
  int iterations = 0;
};

}  // namespace

GeodesicDistance geodesic_distance(const SurfaceMesh& surface, const SurfaceLocation& from, const SurfaceLocation& to,
                                   const GeodesicDistanceOptions& options) {
  if (options.max_iterations < 1 || options.max_iterations > 1000 || !(options.tolerance > 0) ||
      options.tolerance > 1e-3 || options.extra_shots < 0 || options.extra_shots > 20) {
    throw InvalidInput(fmt::format("geodesic_distance: options max_iterations {} (expected [1, 1000]), tolerance {} "
                                   "(expected (0, 1e-3]), extra_shots {} (expected [0, 20])",
                                   options.max_iterations, options.tolerance, options.extra_shots));
  }
  const SurfaceLocation a = detail::checked_location(surface, from, "geodesic_distance (from)");
  const SurfaceLocation b = detail::checked_location(surface, to, "geodesic_distance (to)");
  const Eigen::Vector3d p = position(surface, a);
  const Eigen::Vector3d q = position(surface, b);
  GeodesicDistance result;
  result.euclidean = (q - p).norm();
  const double rounding = 256 * std::numeric_limits<double>::epsilon() * std::max(p.cwiseAbs().maxCoeff(),
                                                                                  q.cwiseAbs().maxCoeff());
  const double tolerance = std::max(options.tolerance * result.euclidean, rounding);
  if (result.euclidean <= rounding) {
    result.status = DistanceStatus::Converged;
    result.miss = result.euclidean;
    result.path.end = a;
    result.path.end_point = p;
    result.path.points = {p};
    return result;
  }

  // The tangent frame of the start triangle, e1 towards the target.
  const Eigen::Vector3d& n0 = surface.face_normal(a.triangle);
  Eigen::Vector3d e1 = (q - p) - (q - p).dot(n0) * n0;
  if (!(e1.norm() > 1e-9 * result.euclidean)) {
    const auto& t = surface.mesh().triangles[a.triangle];
    e1 = surface.mesh().vertices[t[1]] - surface.mesh().vertices[t[0]];
  }
  e1.normalize();
  const Eigen::Vector3d e2 = n0.cross(e1);

  const auto shoot = [&](double angle) {
    Shot shot;
    double length = result.euclidean;
    int stalled = 0;
    for (int it = 0; it < options.max_iterations; ++it) {
      ++shot.iterations;
      SurfacePath path = straightest_geodesic(surface, a, std::cos(angle) * e1 + std::sin(angle) * e2, length,
                                              options.trace);
      const Eigen::Vector3d r = q - path.end_point;
      const double miss = r.norm();
      if (miss < shot.miss) {
        shot.miss = miss;
        shot.path = path;
        stalled = 0;
      } else if (++stalled > kStall) {
        break;
      }
      if (miss <= tolerance && path.status == PathStatus::Completed) {
        shot.converged = true;
        shot.path = std::move(path);
        shot.miss = miss;
        break;
      }
      // Newton in the end triangle's tangent plane. In the unfolded strip the family of straight paths from p
      // turns about p: d(end)/d(length) = t, d(end)/d(angle) = length * (n x t).
      const Eigen::Vector3d& n = surface.face_normal(path.end.triangle);
      const Eigen::Vector3d& t = path.end_direction;
      const Eigen::Vector3d r_t = r - r.dot(n) * n;
      const double travelled = std::max(path.length, 1e-3 * result.euclidean);
      const double d_length = r_t.dot(t);
      const double d_angle = std::clamp(r_t.dot(n.cross(t)) / travelled, -kMaxAngleStep, kMaxAngleStep);
      angle += d_angle;
      length = path.length + d_length;
      if (!(length > 0)) length = 0.5 * travelled;
    }
    return shot;
  };

  const double angle0 = 0;
  const int planned = 1 + options.extra_shots;
  const int most = std::max(planned, 7);
  Shot best;
  for (int k = 0; k < most; ++k) {
    if (k >= planned && best.converged) break;
    const double offset = (k == 0) ? 0.0 : ((k + 1) / 2) * 0.3 * (k % 2 ? 1.0 : -1.0);
    Shot shot = shoot(angle0 + offset);
    result.iterations += shot.iterations;
    const bool better = (shot.converged && (!best.converged || shot.path.length < best.path.length)) ||
                        (!best.converged && !shot.converged && shot.miss < best.miss);
    if (better) best = std::move(shot);
  }
  result.status = best.converged ? DistanceStatus::Converged : DistanceStatus::NotConverged;
  result.miss = best.miss;
  result.distance = best.path.length;
  result.path = std::move(best.path);
  if (!best.converged) {
    result.reason = fmt::format("no straightest geodesic from the start reached the target: the best shot ends "
                                "{:.3g} m away ({})", result.miss, to_string(result.path.status));
  }
  return result;
}

}  // namespace needlekit::geometry
