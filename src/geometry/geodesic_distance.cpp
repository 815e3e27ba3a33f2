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

std::string_view to_string(DistanceStatus status) { return name_of(kDistanceStatusNames, status); }

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

void validate(const GeodesicDistanceOptions& options) {
  if (options.max_iterations < 1 || options.max_iterations > 1000 || !(options.tolerance > 0) ||
      options.tolerance > 1e-3 || options.extra_shots < 0 || options.extra_shots > 20) {
    throw InvalidInput(fmt::format("geodesic_distance: options max_iterations {} (expected [1, 1000]), tolerance {} "
                                   "(expected (0, 1e-3]), extra_shots {} (expected [0, 20])",
                                   options.max_iterations, options.tolerance, options.extra_shots));
  }
}

// The search for the shortest geodesic from p (location a) to q (location b) by shooting straightest geodesics from
// p (Newton on the shot's angle and length), aimed first at q, then along the shortest edge path, and last through
// saddle vertices (two legs that meet at the vertex). Every trace spends `budget` (triangle crossings).
struct GeodesicEnds {
  const SurfaceLocation& a;  // where the geodesic starts (p)
  const SurfaceLocation& b;  // where it ends (q)
};

class GeodesicSearch {
public:
  GeodesicSearch(const SurfaceMesh& surface, GeodesicEnds ends, const GeodesicDistanceOptions& options,
                 std::int64_t& budget, GeodesicDistance& result)
      : surface_(surface), a_(ends.a), b_(ends.b), p_(position(surface, ends.a)), q_(position(surface, ends.b)),
        options_(options), budget_(budget), result_(result), n0_(surface.face_normal(ends.a.triangle)) {
    // The tangent frame of the start triangle, e1 towards the target.
    Eigen::Vector3d e1 = (q_ - p_) - (q_ - p_).dot(n0_) * n0_;
    if (!(e1.norm() > 1e-9 * result_.euclidean)) {
      const auto& t = surface.mesh().triangles[ends.a.triangle];
      e1 = surface.mesh().vertices[t[1]] - surface.mesh().vertices[t[0]];
    }
    e1_ = e1.normalized();
    e2_ = n0_.cross(e1_);
    const double rounding = 256 * std::numeric_limits<double>::epsilon() *
                            std::max(p_.cwiseAbs().maxCoeff(), q_.cwiseAbs().maxCoeff());
    tolerance_ = std::max(options.tolerance * result_.euclidean, rounding);
    // A shortest path crosses each triangle at most once: a longer trace cannot be one.
    trace_ = options.trace;
    trace_.max_steps = static_cast<int>(std::min<std::int64_t>(trace_.max_steps, surface.triangle_count() + 16));
  }

  Shot run() {
    fire(0.0, result_.euclidean, 1 + options_.extra_shots);
    if ((!best_.converged || through_cone_vertex(best_.path)) && options_.graph_fallback && budget_ > 0) {
      aim_along_edge_path();
    }
    if (!best_.converged && options_.saddle_detour && budget_ > 0) detour_through_saddles();
    return std::move(best_);
  }

private:
  // Newton from (angle, length) until the shot ends within the tolerance of q, stalls or runs out of iterations.
  Shot shoot(double angle, double length) {
    Shot shot;
    int stalled = 0;
    for (int it = 0; it < options_.max_iterations && budget_ > 0; ++it) {
      ++shot.iterations;
      SurfacePath path = straightest_geodesic(surface_, a_, std::cos(angle) * e1_ + std::sin(angle) * e2_, length,
                                              trace_);
      budget_ -= static_cast<std::int64_t>(path.triangles.size()) + 1;
      const Eigen::Vector3d r = q_ - path.end_point;
      const double miss = r.norm();
      if (miss < shot.miss) {
        shot.miss = miss;
        shot.path = path;
        stalled = 0;
      } else if (++stalled > kStall) {
        break;
      }
      if (miss <= tolerance_ && path.status == PathStatus::Completed) {
        shot.converged = true;
        shot.path = std::move(path);
        shot.miss = miss;
        break;
      }
      // Newton in the end triangle's tangent plane. In the unfolded strip the family of straight paths from p
      // turns about p: d(end)/d(length) = t, d(end)/d(angle) = length * (n x t).
      const Eigen::Vector3d& n = surface_.face_normal(path.end.triangle);
      const Eigen::Vector3d& t = path.end_direction;
      const Eigen::Vector3d r_t = r - r.dot(n) * n;
      const double travelled = std::max(path.length, 1e-3 * result_.euclidean);
      const double d_length = r_t.dot(t);
      const double d_angle = std::clamp(r_t.dot(n.cross(t)) / travelled, -kMaxAngleStep, kMaxAngleStep);
      angle += d_angle;
      length = path.length + d_length;
      if (!(length > 0)) length = 0.5 * travelled;
    }
    return shot;
  }

  // `planned` shots (at least 7 while none converged off a cone vertex) fanned out around angle0; keeps the best.
  void fire(double angle0, double length0, int planned) {
    for (int k = 0; k < std::max(planned, 7) && budget_ > 0; ++k) {
      if (k >= planned && best_.converged && !through_cone_vertex(best_.path)) break;
      const double offset = (k == 0) ? 0.0 : ((k + 1) / 2) * 0.3 * (k % 2 ? 1.0 : -1.0);
      Shot shot = shoot(angle0 + offset, length0);
      result_.iterations += shot.iterations;
      const bool better = (shot.converged && (!best_.converged || shot.path.length < best_.path.length)) ||
                          (!best_.converged && !shot.converged && shot.miss < best_.miss);
      if (better) best_ = std::move(shot);
    }
  }

  // Aim along the shortest edge path: at its point a quarter of the way along, with its length (an upper bound)
  // shortened by the typical excess of edge paths.
  void aim_along_edge_path() {
    const EdgePath edges = shortest_edge_path(surface_, a_.triangle, p_, b_.triangle, q_);
    result_.graph_distance = std::isfinite(edges.length) ? edges.length : 0;
    if (!std::isfinite(edges.length)) return;
    double walked = 0;
    Eigen::Vector3d aim = edges.points.back();
    for (std::size_t i = 1; i < edges.points.size(); ++i) {
      walked += (edges.points[i] - edges.points[i - 1]).norm();
      aim = edges.points[i];
      if (walked >= 0.25 * edges.length) break;
    }
    Eigen::Vector3d towards = aim - p_;
    towards -= towards.dot(n0_) * n0_;
    if (towards.norm() > 0) fire(std::atan2(towards.dot(e2_), towards.dot(e1_)), 0.95 * edges.length, 1);
  }

  // Through the saddle vertices of the triangles the best shot crossed: two converged legs p -> V and q -> V.
  void detour_through_saddles() {
    std::vector<std::pair<int, int>> corners;  // (triangle, corner)
    for (int t : best_.path.triangles) {
      for (int c = 0; c < 3; ++c) corners.push_back({t, c});
    }
    std::vector<int> seen;
    GeodesicDistanceOptions leg_options = options_;
    leg_options.graph_fallback = false;
    leg_options.saddle_detour = false;
    constexpr int kMaxDetours = 64;
    for (const auto& [t, c] : corners) {
      const int vertex = surface_.mesh().triangles[t][c];
      if (std::find(seen.begin(), seen.end(), vertex) != seen.end()) continue;
      seen.push_back(vertex);
      if (static_cast<int>(seen.size()) > kMaxDetours) break;
      const detail::Fan fan = detail::fan_around(surface_, t, c);
      if (fan.closed && fan.total_angle <= 2 * std::numbers::pi + 1e-9) continue;  // not a saddle
      Eigen::Vector3d corner = Eigen::Vector3d::Zero();
      corner[c] = 1;
      const SurfaceLocation via{t, corner};
      if (budget_ <= 0) break;
      GeodesicDistance first = budgeted_distance(surface_, a_, via, leg_options, budget_);
      result_.iterations += first.iterations;
      if (first.status != DistanceStatus::Converged) continue;
      // The second leg is shot from q back to V: shots from a point reach a vertex more reliably than shots from it.
      GeodesicDistance second = budgeted_distance(surface_, b_, via, leg_options, budget_);
      result_.iterations += second.iterations;
      if (second.status != DistanceStatus::Converged) continue;
      const double length = first.distance + second.distance;
      if (best_.converged && length >= best_.path.length) continue;
      best_.converged = true;
      best_.miss = second.miss;
      best_.path = std::move(first.path);
      best_.path.length = length;
      best_.path.points.insert(best_.path.points.end(), second.path.points.rbegin() + 1, second.path.points.rend());
      best_.path.triangles.insert(best_.path.triangles.end(), second.path.triangles.rbegin(),
                                  second.path.triangles.rend());
      best_.path.end = b_;
      best_.path.end_point = q_;
      const auto& back = second.path.points;
      best_.path.end_direction = back.size() > 1 ? Eigen::Vector3d((back[0] - back[1]).normalized())
                                                 : Eigen::Vector3d::Zero();
      result_.via_vertex = vertex;
    }
  }

  const SurfaceMesh& surface_;
  const SurfaceLocation a_, b_;
  const Eigen::Vector3d p_, q_;
  const GeodesicDistanceOptions& options_;
  std::int64_t& budget_;
  GeodesicDistance& result_;
  const Eigen::Vector3d n0_;
  Eigen::Vector3d e1_, e2_;
  double tolerance_ = 0;
  TraceOptions trace_;
  Shot best_;
};

GeodesicDistance budgeted_distance(const SurfaceMesh& surface, const SurfaceLocation& from, const SurfaceLocation& to,
                                   const GeodesicDistanceOptions& options, std::int64_t& budget) {
  validate(options);
  const SurfaceLocation a = detail::checked_location(surface, from, "geodesic_distance (from)");
  const SurfaceLocation b = detail::checked_location(surface, to, "geodesic_distance (to)");
  const Eigen::Vector3d p = position(surface, a);
  const Eigen::Vector3d q = position(surface, b);
  GeodesicDistance result;
  result.euclidean = (q - p).norm();
  const double rounding = 256 * std::numeric_limits<double>::epsilon() * std::max(p.cwiseAbs().maxCoeff(),
                                                                                  q.cwiseAbs().maxCoeff());
  if (result.euclidean <= rounding) {
    result.status = DistanceStatus::Converged;
    result.miss = result.euclidean;
    result.path.end = a;
    result.path.end_point = p;
    result.path.points = {p};
    return result;
  }
  Shot best = GeodesicSearch(surface, {a, b}, options, budget, result).run();
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
