#include "surface_walk.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <numbers>

#include "needlekit/core/errors.hpp"

namespace needlekit::geometry {

std::string_view to_string(PathStatus status) { return name_of(kPathStatusNames, status); }

Eigen::Vector3d position(const SurfaceMesh& surface, const SurfaceLocation& location) {
  const auto& t = surface.mesh().triangles.at(location.triangle);
  const auto& v = surface.mesh().vertices;
  return location.barycentric[0] * v[t[0]] + location.barycentric[1] * v[t[1]] + location.barycentric[2] * v[t[2]];
}

SurfaceLocation vertex_location(const SurfaceMesh& surface, int vertex) {
  if (vertex < 0 || vertex >= surface.vertex_count()) {
    throw InvalidInput(fmt::format("vertex {} is not in [0, {})", vertex, surface.vertex_count()));
  }
  const int t = surface.vertex_triangle(vertex);
  if (t < 0) throw InvalidInput(fmt::format("vertex {} belongs to no triangle", vertex));
  const auto& tri = surface.mesh().triangles[t];
  const int corner = tri[0] == vertex ? 0 : (tri[1] == vertex ? 1 : 2);
  return {t, Eigen::Vector3d::Unit(corner)};
}

namespace detail {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
// Rates of change of the barycentric coordinates below this fraction of the largest are rounding: the path runs
// along that edge.
constexpr double kRateTolerance = 1e-12;
// Consecutive zero-length steps (turning around a vertex or an edge) after which the walk gives up.
constexpr int kMaxZeroSteps = 64;

const Eigen::Vector3d& corner_position(const SurfaceMesh& s, int t, int c) {
  return s.mesh().vertices[s.mesh().triangles[t][c]];
}

// Barycentric gradients and the unit normal of a triangle.
struct TriangleFrame {
  Eigen::Vector3d normal;
  Eigen::Vector3d gradient[3];
  double twice_area = 0;
  double longest_squared = 0;
};

TriangleFrame frame_of(const SurfaceMesh& s, int t) {
  const Eigen::Vector3d& x0 = corner_position(s, t, 0);
  const Eigen::Vector3d& x1 = corner_position(s, t, 1);
  const Eigen::Vector3d& x2 = corner_position(s, t, 2);
  TriangleFrame f;
  const Eigen::Vector3d cross = (x1 - x0).cross(x2 - x0);
  f.twice_area = cross.norm();
  f.longest_squared = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
  f.normal = f.twice_area > 0 ? Eigen::Vector3d(cross / f.twice_area) : s.face_normal(t);
  if (f.twice_area > 0) {
    // grad b_k = n x (x_{k+2} - x_{k+1}) / (2A): points from the opposite edge towards corner k.
    f.gradient[0] = f.normal.cross(x2 - x1) / f.twice_area;
    f.gradient[1] = f.normal.cross(x0 - x2) / f.twice_area;
    f.gradient[2] = f.normal.cross(x1 - x0) / f.twice_area;
  }
  return f;
}

bool is_degenerate(const TriangleFrame& f, const TraceOptions& options) {
  return !(f.twice_area > options.degenerate_sine * f.longest_squared);
}

Eigen::Vector3d unit_corner(int c) {
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  b[c] = 1;
  return b;
}

void clamp_barycentric(Eigen::Vector3d& b) {
  b = b.cwiseMax(0.0);
  const double sum = b.sum();
  if (sum > 0) b /= sum;
}

}  // namespace

int Fan::index_of(int triangle) const {
  for (std::size_t i = 0; i < wedges.size(); ++i) {
    if (wedges[i].triangle == triangle) return static_cast<int>(i);
  }
  return -1;
}

double Fan::angle_before(int index) const {
  double sum = 0;
  for (int i = 0; i < index; ++i) sum += wedges[i].angle;
  return sum;
}

Fan fan_around(const SurfaceMesh& surface, int triangle, int corner) {
  const auto& tris = surface.mesh().triangles;
  const int vertex = tris[triangle][corner];
  const auto wedge = [&](int t) {
    int c = 0;
    while (tris[t][c] != vertex) ++c;
    const Eigen::Vector3d& v = corner_position(surface, t, c);
    const Eigen::Vector3d e1 = corner_position(surface, t, (c + 1) % 3) - v;
    const Eigen::Vector3d e2 = corner_position(surface, t, (c + 2) % 3) - v;
    return FanWedge{t, c, std::atan2(e1.cross(e2).norm(), e1.dot(e2))};
  };
  Fan fan;
  fan.wedges.push_back(wedge(triangle));
  const int limit = surface.triangle_count();
  // Counter-clockwise: across the edge from corner c+2 to corner c.
  for (int t = triangle, guard = 0; guard < limit; ++guard) {
    const FanWedge& last = fan.wedges.back();
    t = surface.neighbor(last.triangle, (last.corner + 2) % 3);
    if (t == triangle) {
      fan.closed = true;
      break;
    }
    if (t < 0) break;
    fan.wedges.push_back(wedge(t));
  }
  if (!fan.closed) {
    // Clockwise from the start: across the edge from corner c to corner c+1.
    std::vector<FanWedge> before;
    FanWedge current = fan.wedges.front();
    for (int guard = 0; guard < limit; ++guard) {
      const int t = surface.neighbor(current.triangle, current.corner);
      if (t < 0 || t == triangle) break;
      current = wedge(t);
      before.push_back(current);
    }
    fan.wedges.insert(fan.wedges.begin(), before.rbegin(), before.rend());
  }
  for (const auto& w : fan.wedges) fan.total_angle += w.angle;
  return fan;
}

double angle_in_wedge(const SurfaceMesh& surface, int triangle, int corner, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d& v = corner_position(surface, triangle, corner);
  const Eigen::Vector3d first = (corner_position(surface, triangle, (corner + 1) % 3) - v).normalized();
  const Eigen::Vector3d& n = surface.face_normal(triangle);
  return std::atan2(n.dot(first.cross(direction)), first.dot(direction));
}

Eigen::Vector3d direction_in_wedge(const SurfaceMesh& surface, const FanWedge& wedge, double angle) {
  // Strictly inside, so that the next step leaves through the opposite edge rather than turning on the spot.
  const double margin = 1e-12 * std::max(wedge.angle, 1e-300);
  angle = std::clamp(angle, margin, wedge.angle - margin);
  const Eigen::Vector3d& v = corner_position(surface, wedge.triangle, wedge.corner);
  const Eigen::Vector3d first = (corner_position(surface, wedge.triangle, (wedge.corner + 1) % 3) - v).normalized();
  const Eigen::Vector3d& n = surface.face_normal(wedge.triangle);
  return (std::cos(angle) * first + std::sin(angle) * n.cross(first)).normalized();
}

std::optional<std::pair<int, double>> wedge_at(const Fan& fan, double angle) {
  if (fan.wedges.empty() || !(fan.total_angle > 0)) return std::nullopt;
  if (fan.closed) {
    angle = std::fmod(angle, fan.total_angle);
    if (angle < 0) angle += fan.total_angle;
  } else if (angle < 0 || angle > fan.total_angle) {
    return std::nullopt;
  }
  double before = 0;
  for (std::size_t i = 0; i < fan.wedges.size(); ++i) {
    if (angle <= before + fan.wedges[i].angle || i + 1 == fan.wedges.size()) {
      return std::pair<int, double>{static_cast<int>(i), angle - before};
    }
    before += fan.wedges[i].angle;
  }
  return std::nullopt;
}

Eigen::Vector3d unfolded_direction(const SurfaceMesh& surface, int from, int edge, int next,
                                   const Eigen::Vector3d& d) {
  const Eigen::Vector3d u =
      (corner_position(surface, from, (edge + 1) % 3) - corner_position(surface, from, edge)).normalized();
  const Eigen::Vector3d& n1 = surface.face_normal(from);
  const Eigen::Vector3d& n2 = surface.face_normal(next);
  // n x u points into `from` (counter-clockwise orientation) and out of `next` (which runs the edge backwards):
  // the component across the edge keeps its sign relative to those, i.e. the path crosses.
  return (d.dot(u) * u + d.dot(n1.cross(u)) * n2.cross(u)).normalized();
}

SurfaceLocation checked_location(const SurfaceMesh& surface, const SurfaceLocation& location, const char* what) {
  if (location.triangle < 0 || location.triangle >= surface.triangle_count()) {
    throw InvalidInput(fmt::format("{}: start triangle {} is not in [0, {})", what, location.triangle,
                                   surface.triangle_count()));
  }
  const Eigen::Vector3d& b = location.barycentric;
  if (!b.allFinite() || b.minCoeff() < -1e-6 || std::abs(b.sum() - 1) > 1e-6) {
    throw InvalidInput(fmt::format("{}: start barycentric coordinates ({}, {}, {}) must be non-negative and sum to "
                                   "one", what, b[0], b[1], b[2]));
  }
  SurfaceLocation out = location;
  clamp_barycentric(out.barycentric);
  return out;
}

namespace {

// One trace across the triangles (walk below): the current triangle t, barycentric position b and direction d, and
// the path so far. Each crossing either ends the trace (a finished path) or moves on to the next triangle.
class Walker {
public:
  Walker(const SurfaceMesh& surface, const SurfaceLocation& start, const Eigen::Vector3d& direction,
         const WalkRule& rule, const TraceOptions& options)
      : surface_(surface), rule_(rule), options_(options), t_(start.triangle), b_(start.barycentric), d_(direction) {
    path_.points.push_back(position(surface, {t_, b_}));
  }

  SurfacePath run(double length) {
    if (is_degenerate(frame_of(surface_, t_), options_)) {
      return finish(PathStatus::DegenerateTriangle, fmt::format("the start triangle {} is degenerate", t_));
    }
    if (std::optional<SurfacePath> ended = leave_start_vertex(length)) return *ended;
    double remaining = length;
    int zero_steps = 0;
    for (int step = 0; step < options_.max_steps; ++step) {
      const TriangleFrame f = frame_of(surface_, t_);
      Eigen::Vector3d rate;
      for (int k = 0; k < 3; ++k) rate[k] = f.gradient[k].dot(d_);
      const double scale = rate.cwiseAbs().maxCoeff();
      int exit_corner = -1;
      double exit_t = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        if (rate[k] < -kRateTolerance * scale) {
          const double tk = std::max(b_[k], 0.0) / -rate[k];
          if (tk < exit_t) exit_t = tk, exit_corner = k;
        }
      }
      if (exit_corner < 0 || remaining <= exit_t) {
        b_ += remaining * rate;
        clamp_barycentric(b_);
        path_.length += remaining;
        return finish(PathStatus::Completed, "");
      }
      Eigen::Vector3d crossing = b_ + exit_t * rate;
      crossing[exit_corner] = 0;
      clamp_barycentric(crossing);
      b_ = crossing;
      path_.length += exit_t;
      remaining -= exit_t;
      path_.points.push_back(position(surface_, {t_, b_}));
      path_.triangles.push_back(t_);
      zero_steps = exit_t > 1e-14 * std::sqrt(f.longest_squared) ? 0 : zero_steps + 1;
      if (zero_steps > kMaxZeroSteps) {
        return finish(PathStatus::StepLimit,
                      fmt::format("no progress at triangle {} after {} zero-length steps", t_, zero_steps));
      }
      if (std::optional<SurfacePath> ended = cross(exit_corner)) return *ended;
    }
    return finish(PathStatus::StepLimit, fmt::format("crossed more than {} triangles", options_.max_steps));
  }

private:
  SurfacePath finish(PathStatus status, std::string reason) {
    path_.status = status;
    path_.reason = std::move(reason);
    path_.end = {t_, b_};
    path_.end_point = position(surface_, path_.end);
    path_.end_direction = d_;
    if ((path_.points.back() - path_.end_point).norm() > 0 || path_.points.size() == 1) {
      path_.points.push_back(path_.end_point);
      path_.triangles.push_back(t_);
    }
    return path_;
  }

  // A start at a vertex: the rule picks the wedge the direction leaves through.
  std::optional<SurfacePath> leave_start_vertex(double length) {
    for (int c = 0; c < 3; ++c) {
      if (b_[c] < 1 - options_.vertex_tolerance || length == 0) continue;
      const Fan fan = fan_around(surface_, t_, c);
      std::string reason;
      const auto leave = rule_.leave_vertex(surface_, fan, fan.index_of(t_), d_, reason);
      if (!leave) return finish(PathStatus::HitBoundary, reason);
      t_ = leave->triangle;
      d_ = leave->direction;
      b_ = unit_corner(fan.wedges[fan.index_of(t_)].corner);
      break;
    }
    return std::nullopt;
  }

  // On the edge opposite exit_corner: through a vertex (the crossing lies on an end of the exit edge) or across the
  // edge into the neighbour; the finished path when the trace cannot go on.
  std::optional<SurfacePath> cross(int exit_corner) {
    const auto& tris = surface_.mesh().triangles;
    const double vertex_tol = options_.vertex_tolerance;
    const int c1 = (exit_corner + 1) % 3, c2 = (exit_corner + 2) % 3;
    const int vertex_corner = b_[c2] <= vertex_tol ? c1 : (b_[c1] <= vertex_tol ? c2 : -1);
    if (vertex_corner >= 0) {
      b_ = unit_corner(vertex_corner);
      path_.points.back() = position(surface_, {t_, b_});
      const Fan fan = fan_around(surface_, t_, vertex_corner);
      path_.vertex_crossings.push_back({tris[t_][vertex_corner], fan.total_angle});
      std::string reason;
      const auto through = rule_.through_vertex(surface_, fan, fan.index_of(t_), d_, reason);
      if (!through) return finish(PathStatus::HitBoundary, reason);
      if (is_degenerate(frame_of(surface_, through->triangle), options_)) {
        return finish(PathStatus::DegenerateTriangle,
                      fmt::format("triangle {} beyond vertex {} is degenerate", through->triangle,
                                  tris[t_][vertex_corner]));
      }
      t_ = through->triangle;
      d_ = through->direction;
      b_ = unit_corner(fan.wedges[fan.index_of(t_)].corner);
      return std::nullopt;
    }
    // Across the edge from corner c1 to corner c2 (edge index c1).
    const int next = surface_.neighbor(t_, c1);
    if (next < 0) {
      return finish(PathStatus::HitBoundary, fmt::format("reached the boundary edge {}-{} of triangle {}",
                                                         tris[t_][c1], tris[t_][c2], t_));
    }
    if (is_degenerate(frame_of(surface_, next), options_)) {
      return finish(PathStatus::DegenerateTriangle,
                    fmt::format("triangle {} across edge {}-{} is degenerate", next, tris[t_][c1], tris[t_][c2]));
    }
    Eigen::Vector3d nb = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) {
      if (tris[next][c] == tris[t_][c1]) nb[c] = b_[c1];
      if (tris[next][c] == tris[t_][c2]) nb[c] = b_[c2];
    }
    d_ = rule_.across_edge(surface_, t_, c1, next, d_);
    t_ = next;
    b_ = nb;
    return std::nullopt;
  }

  const SurfaceMesh& surface_;
  const WalkRule& rule_;
  const TraceOptions& options_;
  int t_;
  Eigen::Vector3d b_, d_;
  SurfacePath path_;
};

}  // namespace

SurfacePath walk(const SurfaceMesh& surface, const SurfaceLocation& start, const Eigen::Vector3d& direction,
                 double length, const WalkRule& rule, const TraceOptions& options) {
  if (options.max_steps < 1 || !(options.vertex_tolerance >= 0 && options.vertex_tolerance <= 1e-3) ||
      !(options.degenerate_sine >= 0 && options.degenerate_sine <= 1e-3)) {
    throw InvalidInput(fmt::format("trace options: max_steps {} (expected >= 1), vertex_tolerance {} (expected "
                                   "[0, 1e-3]), degenerate_sine {} (expected [0, 1e-3])", options.max_steps,
                                   options.vertex_tolerance, options.degenerate_sine));
  }
  return Walker(surface, start, direction, rule, options).run(length);
}

}  // namespace detail
}  // namespace needlekit::geometry
