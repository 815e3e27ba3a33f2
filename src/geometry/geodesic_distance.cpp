#include "needlekit/geometry/geodesic_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <queue>
#include <vector>

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

// A path through a vertex whose total angle is below 2 pi can be shortened by passing beside it: it is a geodesic
// but never a shortest path, so the search goes on.
bool through_cone_vertex(const SurfacePath& path) {
  return std::any_of(path.vertex_crossings.begin(), path.vertex_crossings.end(),
                     [](const VertexCrossing& v) { return v.total_angle < 2 * std::numbers::pi - 1e-9; });
}

struct Shot {
  bool converged = false;
  double miss = std::numeric_limits<double>::infinity();
  SurfacePath path;
  int iterations = 0;
};

// The shortest path along mesh edges from p (in triangle `a`) to q (in triangle `b`), entering and leaving the
// graph through the triangles' corners; empty if q is not reachable.
struct EdgePath {
  double length = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector3d> points;  // p, the vertices, q
};

EdgePath shortest_edge_path(const SurfaceMesh& surface, int a, const Eigen::Vector3d& p, int b,
                            const Eigen::Vector3d& q) {
  const auto& tris = surface.mesh().triangles;
  const auto& v = surface.mesh().vertices;
  const int nv = surface.vertex_count();
  // Vertex adjacency in compressed rows (each undirected edge appears from both triangles: harmless duplicates).
  std::vector<int> start(nv + 1, 0), next;
  for (const auto& t : tris) {
    for (int c = 0; c < 3; ++c) start[t[c] + 1] += 2;
  }
  for (int i = 0; i < nv; ++i) start[i + 1] += start[i];
  next.resize(start[nv]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& t : tris) {
    for (int c = 0; c < 3; ++c) {
      next[fill[t[c]]++] = t[(c + 1) % 3];
      next[fill[t[c]]++] = t[(c + 2) % 3];
    }
  }
  std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
  std::vector<int> from(nv, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int c = 0; c < 3; ++c) {
    const int i = tris[a][c];
    dist[i] = std::min(dist[i], (v[i] - p).norm());
    queue.push({dist[i], i});
  }
  EdgePath best;
  int best_end = -1;
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    if (d >= best.length) break;
    for (int c = 0; c < 3; ++c) {
      if (tris[b][c] == i && d + (q - v[i]).norm() < best.length) {
        best.length = d + (q - v[i]).norm();
        best_end = i;
      }
    }
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const int j = next[k];
      const double dj = d + (v[j] - v[i]).norm();
      if (dj < dist[j]) {
        dist[j] = dj;
        from[j] = i;
        queue.push({dj, j});
      }
    }
  }
  if (best_end < 0) return best;
  best.points.push_back(q);
  for (int i = best_end; i >= 0; i = from[i]) best.points.push_back(v[i]);
  best.points.push_back(p);
  std::reverse(best.points.begin(), best.points.end());
  return best;
}

}  // namespace

namespace {

GeodesicDistance budgeted_distance(const SurfaceMesh& surface, const SurfaceLocation& from, const SurfaceLocation& to,
                                   const GeodesicDistanceOptions& options, std::int64_t& budget);

}  // namespace

GeodesicDistance geodesic_distance(const SurfaceMesh& surface, const SurfaceLocation& from, const SurfaceLocation& to,
                                   const GeodesicDistanceOptions& options) {
  if (options.max_crossings < 1) {
    throw InvalidInput(fmt::format("geodesic_distance: max_crossings {}, expected >= 1", options.max_crossings));
  }
  std::int64_t budget = options.max_crossings;
  GeodesicDistance result = budgeted_distance(surface, from, to, options, budget);
  if (result.status != DistanceStatus::Converged && budget <= 0) {
    result.reason += fmt::format("; the work budget of {} triangle crossings (max_crossings) was spent",
                                 options.max_crossings);
  }
  return result;
}

namespace {

GeodesicDistance budgeted_distance(const SurfaceMesh& surface, const SurfaceLocation& from, const SurfaceLocation& to,
                                   const GeodesicDistanceOptions& options, std::int64_t& budget) {
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

  // A shortest path crosses each triangle at most once: a longer trace cannot be one.
  TraceOptions trace = options.trace;
  trace.max_steps = static_cast<int>(std::min<std::int64_t>(trace.max_steps, surface.triangle_count() + 16));
  const auto shoot = [&](double angle, double length) {
    Shot shot;
    int stalled = 0;
    for (int it = 0; it < options.max_iterations && budget > 0; ++it) {
      ++shot.iterations;
      SurfacePath path = straightest_geodesic(surface, a, std::cos(angle) * e1 + std::sin(angle) * e2, length,
                                              trace);
      budget -= static_cast<std::int64_t>(path.triangles.size()) + 1;
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

  Shot best;
  const auto fire = [&](double angle0, double length0, int planned) {
    for (int k = 0; k < std::max(planned, 7) && budget > 0; ++k) {
      if (k >= planned && best.converged && !through_cone_vertex(best.path)) break;
      const double offset = (k == 0) ? 0.0 : ((k + 1) / 2) * 0.3 * (k % 2 ? 1.0 : -1.0);
      Shot shot = shoot(angle0 + offset, length0);
      result.iterations += shot.iterations;
      const bool better = (shot.converged && (!best.converged || shot.path.length < best.path.length)) ||
                          (!best.converged && !shot.converged && shot.miss < best.miss);
      if (better) best = std::move(shot);
    }
  };
  fire(0.0, result.euclidean, 1 + options.extra_shots);
  if ((!best.converged || through_cone_vertex(best.path)) && options.graph_fallback && budget > 0) {
    // Aim along the shortest edge path: at its point a quarter of the way along, with its length (an upper
    // bound) shortened by the typical excess of edge paths.
    const EdgePath edges = shortest_edge_path(surface, a.triangle, p, b.triangle, q);
    result.graph_distance = std::isfinite(edges.length) ? edges.length : 0;
    if (std::isfinite(edges.length)) {
      double walked = 0;
      Eigen::Vector3d aim = edges.points.back();
      for (std::size_t i = 1; i < edges.points.size(); ++i) {
        walked += (edges.points[i] - edges.points[i - 1]).norm();
        aim = edges.points[i];
        if (walked >= 0.25 * edges.length) break;
      }
      Eigen::Vector3d towards = aim - p;
      towards -= towards.dot(n0) * n0;
      if (towards.norm() > 0) fire(std::atan2(towards.dot(e2), towards.dot(e1)), 0.95 * edges.length, 1);
    }
  }
  if (!best.converged && options.saddle_detour && budget > 0) {
    // Vertices of the triangles the best shot crossed, and of the edge path: those where a shortest path may bend.
    std::vector<std::pair<int, int>> corners;  // (triangle, corner)
    for (int t : best.path.triangles) {
      for (int c = 0; c < 3; ++c) corners.push_back({t, c});
    }
    std::vector<int> seen;
    GeodesicDistanceOptions leg_options = options;
    leg_options.graph_fallback = false;
    leg_options.saddle_detour = false;
    constexpr int kMaxDetours = 64;
    for (const auto& [t, c] : corners) {
      const int vertex = surface.mesh().triangles[t][c];
      if (std::find(seen.begin(), seen.end(), vertex) != seen.end()) continue;
      seen.push_back(vertex);
      if (static_cast<int>(seen.size()) > kMaxDetours) break;
      const detail::Fan fan = detail::fan_around(surface, t, c);
      if (fan.closed && fan.total_angle <= 2 * std::numbers::pi + 1e-9) continue;  // not a saddle
      Eigen::Vector3d corner = Eigen::Vector3d::Zero();
      corner[c] = 1;
      const SurfaceLocation via{t, corner};
      if (budget <= 0) break;
      GeodesicDistance first = budgeted_distance(surface, a, via, leg_options, budget);
      result.iterations += first.iterations;
      if (first.status != DistanceStatus::Converged) continue;
      // The second leg is shot from q back to V: shots from a point reach a vertex more reliably than shots from it.
      GeodesicDistance second = budgeted_distance(surface, b, via, leg_options, budget);
      result.iterations += second.iterations;
      if (second.status != DistanceStatus::Converged) continue;
      const double length = first.distance + second.distance;
      if (best.converged && length >= best.path.length) continue;
      best.converged = true;
      best.miss = second.miss;
      best.path = std::move(first.path);
      best.path.length = length;
      best.path.points.insert(best.path.points.end(), second.path.points.rbegin() + 1, second.path.points.rend());
      best.path.triangles.insert(best.path.triangles.end(), second.path.triangles.rbegin(),
                                 second.path.triangles.rend());
      best.path.end = b;
      best.path.end_point = q;
      const auto& back = second.path.points;
      best.path.end_direction = back.size() > 1 ? Eigen::Vector3d((back[0] - back[1]).normalized())
                                                : Eigen::Vector3d::Zero();
      result.via_vertex = vertex;
    }
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

}  // namespace

}  // namespace needlekit::geometry
