#include "needlekit/insertion/post_puncture_force.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <optional>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/post_puncture_parameters.hpp"

namespace needlekit::insertion {
namespace {

const Eigen::Vector3d& vertex(const geometry::TriangleMesh& mesh, int i) {
  return mesh.vertices[static_cast<std::size_t>(i)];
}

// A unit vector perpendicular to the unit vector d.
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& d) {
  const Eigen::Vector3d trial = std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (trial - trial.dot(d) * d).normalized();
}

double full_load(const LoadedTriangle& t) {
  return t.weight * t.area * (t.load[0] + t.load[1] + t.load[2]) / 3.0;  // Eqs 3.19-3.20: the load prism's volume
}

double first_depth(const LoadedTriangle& t) { return std::min({t.depth[0], t.depth[1], t.depth[2]}); }
double last_depth(const LoadedTriangle& t) { return std::max({t.depth[0], t.depth[1], t.depth[2]}); }

// ∫ p/(K·S) dA over the part of the triangle with a <= h: the load is linear over the triangle, the part is a
// triangle (h below the middle vertex) or the triangle minus one (above it); each integral is area × mean load.
double clipped_load(const LoadedTriangle& t, double h) {
  std::array<int, 3> o{0, 1, 2};
  std::sort(o.begin(), o.end(), [&](int i, int j) { return t.depth[i] < t.depth[j]; });
  const double a0 = t.depth[o[0]], a1 = t.depth[o[1]], a2 = t.depth[o[2]];
  const double f0 = t.load[o[0]], f1 = t.load[o[1]], f2 = t.load[o[2]];
  if (h <= a0) return 0;
  if (h >= a2) return full_load(t);
  if (h <= a1) {
    const double t1 = (h - a0) / (a1 - a0), t2 = (h - a0) / (a2 - a0);
    return t.weight * t.area * t1 * t2 * (3 * f0 + t1 * (f1 - f0) + t2 * (f2 - f0)) / 3.0;
  }
  const double u0 = (a2 - h) / (a2 - a0), u1 = (a2 - h) / (a2 - a1);
  return full_load(t) - t.weight * t.area * u0 * u1 * (3 * f2 + u0 * (f0 - f2) + u1 * (f1 - f2)) / 3.0;
}

// The support function of the tip's footprint (the tip vertices projected on the plane normal to d, relative to the
// axis): x_open(e) = max_j r_j·e, by a binary search over the edge normals of the footprint's convex hull (the tip of
// a fine needle mesh has hundreds of vertices and every β-triangle asks).
class TipFootprint {
public:
  TipFootprint(const std::vector<Eigen::Vector3d>& radial, const Eigen::Vector3d& d) {
    u1_ = any_perpendicular(d);
    u2_ = d.cross(u1_);
    std::vector<Eigen::Vector2d> points;
    points.reserve(radial.size());
    for (const auto& r : radial) points.emplace_back(r.dot(u1_), r.dot(u2_));
    std::sort(points.begin(), points.end(),
              [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
    };
    // Andrew's monotone chain: counter-clockwise hull without collinear points.
    std::vector<Eigen::Vector2d> hull(2 * points.size() + 1);
    std::size_t k = 0;
    for (const auto& p : points) {
      while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
      hull[k++] = p;
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
      while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
      hull[k++] = points[i];
    }
    hull.resize(points.size() > 1 ? k - 1 : points.size());
    hull_ = hull;
    if (hull_.size() < 8) return;  // small: brute force
    const std::size_t m = hull_.size();
    std::vector<std::pair<double, std::size_t>> normals(m);  // outward normal angle of edge i -> i+1
    for (std::size_t i = 0; i < m; ++i) {
      const Eigen::Vector2d edge = hull_[(i + 1) % m] - hull_[i];
      normals[i] = {std::atan2(-edge.x(), edge.y()), i};
    }
    std::sort(normals.begin(), normals.end());
    angles_.reserve(m);
    edges_.reserve(m);
    for (const auto& [angle, edge] : normals) {
      angles_.push_back(angle);
      edges_.push_back(edge);
    }
  }

  double operator()(const Eigen::Vector3d& e) const {
    const Eigen::Vector2d direction(e.dot(u1_), e.dot(u2_));
    double best = 0;  // x_open >= 0: the axis itself is always open
    if (angles_.empty()) {
      for (const auto& p : hull_) best = std::max(best, p.dot(direction));
      return best;
    }
    // The extreme vertex for a direction between the normals of edges i−1 and i is the start of edge i.
    const double phi = std::atan2(direction.y(), direction.x());
    std::size_t i = static_cast<std::size_t>(std::lower_bound(angles_.begin(), angles_.end(), phi) - angles_.begin());
    if (i == angles_.size()) i = 0;
    const std::size_t m = hull_.size(), v = edges_[i];
    for (std::size_t j : {(v + m - 1) % m, v, (v + 1) % m}) best = std::max(best, hull_[j].dot(direction));
    return best;
  }

private:
  Eigen::Vector3d u1_, u2_;
  std::vector<Eigen::Vector2d> hull_;
  std::vector<double> angles_;       // ascending
  std::vector<std::size_t> edges_;   // hull edge of each angle
};

}  // namespace

double load_prism_volume(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3, double h1,
                         double h2, double h3) {
  const Eigen::Vector3d normal_area = (p2 - p1).cross(p3 - p1);
  const Eigen::Vector3d n = normal_area.normalized();
  const Eigen::Vector3d q1 = p1 + h1 * n, q2 = p2 + h2 * n, q3 = p3 + h3 * n;
  // Eq 3.19 for each tetrahedron of the pentahedron p1 p2 p3 q1 q2 q3; Eq 3.20 sums them.
  auto tetrahedron = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                        const Eigen::Vector3d& d) { return std::abs((a - d).dot((b - d).cross(c - d))) / 6.0; };
  return tetrahedron(p1, p2, p3, q1) + tetrahedron(p2, p3, q1, q2) + tetrahedron(p3, q1, q2, q3);
}

namespace {

void validate(const PostPunctureOptions& options) {
  check_ranges(kPostPunctureParameters, options, "post_puncture");
}

using Corners = std::array<Eigen::Vector3d, 3>;

// The needle's frame for Algorithm 3.1: the insertion direction d, the tip plane, the channel axis through the
// centre of the tip, the tip's footprint and the reference radius R.
class NeedleFrame {
public:
  NeedleFrame(const geometry::TriangleMesh& needle, const Eigen::Vector3d& d, const PostPunctureOptions& options)
      : d_(d), options_(options) {
    // Axial positions: a(P) = distance behind the tip plane.
    const std::size_t nv = needle.vertices.size();
    std::vector<double> along(nv);
    for (std::size_t i = 0; i < nv; ++i) along[i] = needle.vertices[i].dot(d);
    top_ = *std::max_element(along.begin(), along.end());
    length_ = top_ - *std::min_element(along.begin(), along.end());
    tip_band_ = options.tip_tolerance * length_;
    std::vector<int> tip_vertices;
    for (std::size_t i = 0; i < nv; ++i) {
      if (top_ - along[i] <= tip_band_) tip_vertices.push_back(static_cast<int>(i));
    }
    axis_point_ = options.axis_point;
    if (!axis_point_.allFinite()) {
      axis_point_.setZero();
      for (int i : tip_vertices) axis_point_ += vertex(needle, i);
      axis_point_ /= static_cast<double>(tip_vertices.size());
    }
    std::vector<Eigen::Vector3d> tip_radial;
    tip_radial.reserve(tip_vertices.size());
    for (int i : tip_vertices) tip_radial.push_back(radial(vertex(needle, i)));
    x_open_.emplace(tip_radial, d);
    radius_ = options.reference_radius;
    if (radius_ == 0)
      for (const auto& p : needle.vertices) radius_ = std::max(radius_, radial(p).norm());
    if (!(radius_ > 0))
      throw InvalidInput("needle mesh: every vertex lies on the channel axis; expected a needle of non-zero width");
  }

  // The part of p - axis point normal to d.
  Eigen::Vector3d radial(const Eigen::Vector3d& p) const {
    Eigen::Vector3d r = p - axis_point_;
    return Eigen::Vector3d(r - r.dot(d_) * d_);
  }
  double length() const { return length_; }
  double radius() const { return radius_; }
  const Eigen::Vector3d& axis_point() const { return axis_point_; }

  // One loaded (sub-)triangle with corners p of mesh triangle `parent`.
  LoadedTriangle loaded(int parent, const Corners& p, bool alpha) const {
    LoadedTriangle loaded;
    const Eigen::Vector3d normal_area = (p[1] - p[0]).cross(p[2] - p[0]);
    const Eigen::Vector3d n = normal_area.normalized();
    loaded.triangle = parent;
    loaded.alpha = alpha;
    loaded.area = 0.5 * normal_area.norm();
    loaded.weight = options_.axial_component ? n.dot(d_) : 1.0;
    for (int k = 0; k < 3; ++k) loaded.depth[k] = top_ - p[static_cast<std::size_t>(k)].dot(d_);
    if (alpha) {
      loaded.load = {1.0, 1.0, 1.0};  // Eq 3.18: uniform pressure K·S
    } else {
      beta_loads(p, n, loaded);
    }
    return loaded;
  }

private:
  // Algorithm 3.1 on a β-triangle: the load f_T/(K·S) at its corners and its case.
  void beta_loads(const Corners& p, const Eigen::Vector3d& n, LoadedTriangle& loaded) const {
    // Reference plane through the axis and the centroid CG_i: in-plane unit e toward CG_i.
    const Eigen::Vector3d centroid = (p[0] + p[1] + p[2]) / 3.0;
    Eigen::Vector3d e = radial(centroid);
    if (e.norm() <= 1e-12 * radius_) e = n - n.dot(d_) * d_;  // centroid on the axis: the normal's radial part
    e = e.norm() > 0 ? Eigen::Vector3d(e.normalized()) : any_perpendicular(d_);
    // Projections Q_k: a (behind the tip) and x (from the axis, toward CG_i).
    std::array<double, 3> a{}, x{};
    std::array<bool, 3> on_tip{};
    int tip_count = 0;
    for (int k = 0; k < 3; ++k) {
      a[k] = loaded.depth[k];
      x[k] = radial(p[static_cast<std::size_t>(k)]).dot(e);
      on_tip[k] = a[k] <= tip_band_;
      tip_count += on_tip[k] ? 1 : 0;
    }
    loaded.beta_case = tip_count == 1 ? BetaCase::OneVertexOnTip
                       : tip_count >= 2 ? BetaCase::TwoVerticesOnTip
                                        : BetaCase::NoVertexOnTip;
    // Q1: the vertex nearest the tip.
    int q1 = 0;
    for (int k = 1; k < 3; ++k)
      if (a[k] < a[q1] || (a[k] == a[q1] && x[k] < x[q1])) q1 = k;
    // The opening line: the edge of the tip in this plane.
    const double b = std::max(0.0, x[q1] - (*x_open_)(e));
    // The meridian slope of the triangle itself (for edges across the meridian, where an edge angle means nothing):
    // tan θ_T = (n·d)/(n·e).
    const double theta_triangle = std::atan2(std::max(n.dot(d_), 0.0), std::abs(n.dot(e)));
    const double degenerate_axial = 1e-9 * length_;
    std::array<double, 3> theta{}, widening{};
    for (int k = 0; k < 3; ++k) {
      if (k == q1) continue;
      const double da = a[k] - a[q1], dx = x[k] - x[q1];
      if (da > degenerate_axial) {
        theta[k] = std::atan2(dx, da);  // angle between the axis and Q1Qk
        widening[k] = dx;               // a·tanθ
      } else {
        theta[k] = theta_triangle;
        widening[k] = 0;
      }
    }
    const int k2 = (q1 + 1) % 3, k3 = (q1 + 2) % 3;
    std::array<double, 3> delta{};
    delta[q1] = b / std::cos(0.5 * (theta[k2] + theta[k3]));  // f_T(P1) = K·S·b/cos((θ2 + θ3)/2)
    for (int k : {k2, k3}) delta[k] = widening[k] + b / std::cos(theta[k]);  // f_T(P_k) = K·S·(a·tanθ + b/cosθ)
    for (int k = 0; k < 3; ++k) {
      double load = on_tip[k] ? 0.0 : std::max(0.0, delta[k]) / radius_;  // f_T = 0 on the needle's tip
      if (!std::isfinite(load)) load = options_.cap_at_cutting_pressure ? 1.0 : 0.0;
      if (options_.cap_at_cutting_pressure) load = std::min(load, 1.0);
      loaded.load[k] = load;
    }
  }

  Eigen::Vector3d d_;
  const PostPunctureOptions& options_;
  double top_ = 0, length_ = 0, tip_band_ = 0, radius_ = 0;
  Eigen::Vector3d axis_point_;
  std::optional<TipFootprint> x_open_;  // the support function of the tip's footprint
};

// Long triangles (a bevel face triangulated edge to edge) are bisected at the midpoint of their longest edge until
// no edge exceeds max_edge, so that Algorithm 3.1 sees triangles small against the load's variation.
void add_subdivided(const NeedleFrame& frame, double max_edge, int parent, const Corners& p, bool alpha, int level,
                    PostPunctureLoads& loads) {
  const std::array<double, 3> edge{(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()};
  const int k = static_cast<int>(std::max_element(edge.begin(), edge.end()) - edge.begin());
  if (max_edge <= 0 || edge[static_cast<std::size_t>(k)] <= max_edge || level >= 48) {
    const LoadedTriangle loaded = frame.loaded(parent, p, alpha);
    if (alpha) {
      loads.alpha_area += loaded.area;
    } else {
      ++loads.case_counts[static_cast<int>(loaded.beta_case)];
    }
    loads.triangles.push_back(loaded);
    return;
  }
  // Split edge k (corners k, k+1) at its midpoint m: (k, m, k+2) and (m, k+1, k+2), orientation kept.
  const auto i = static_cast<std::size_t>(k), j = static_cast<std::size_t>((k + 1) % 3),
             l = static_cast<std::size_t>((k + 2) % 3);
  const Eigen::Vector3d m = 0.5 * (p[i] + p[j]);
  add_subdivided(frame, max_edge, parent, Corners{p[i], m, p[l]}, alpha, level + 1, loads);
  add_subdivided(frame, max_edge, parent, Corners{m, p[j], p[l]}, alpha, level + 1, loads);
}

// Tables for evaluation at many depths: triangles by their first and by their last depth.
void build_depth_tables(PostPunctureLoads& loads) {
  const std::size_t n = loads.triangles.size();
  std::vector<std::pair<double, int>> first(n), last(n);
  for (std::size_t i = 0; i < n; ++i) {
    first[i] = {first_depth(loads.triangles[i]), static_cast<int>(i)};
    last[i] = {last_depth(loads.triangles[i]), static_cast<int>(i)};
  }
  std::sort(first.begin(), first.end());
  std::sort(last.begin(), last.end());
  loads.by_first_depth.resize(n);
  loads.last_depth_sorted.resize(n);
  loads.full_prefix.assign(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    loads.by_first_depth[i] = first[i].second;
    loads.last_depth_sorted[i] = last[i].first;
    loads.full_prefix[i + 1] = loads.full_prefix[i] + full_load(loads.triangles[static_cast<std::size_t>(last[i].second)]);
  }
}

}  // namespace

PostPunctureLoads post_puncture_loads(const geometry::TriangleMesh& needle,
                                      const TriangleClassificationOptions& classification,
                                      const PostPunctureOptions& options, const geometry::SurfaceMesh* surface) {
  validate(options);
  PostPunctureLoads loads;
  loads.classification = classify_triangles(needle, classification, surface);
  const NeedleFrame frame(needle, loads.classification.insertion_direction, options);
  loads.needle_length = frame.length();
  loads.axis_point = frame.axis_point();
  loads.reference_radius = frame.radius();
  const auto& classes = loads.classification;
  loads.triangles.reserve(classes.alpha.size() + classes.beta.size());
  const double max_edge = options.max_edge_fraction * loads.needle_length;
  for (bool alpha : {true, false})
    for (int t : alpha ? classes.alpha : classes.beta) {
      const auto& tri = needle.triangles[static_cast<std::size_t>(t)];
      add_subdivided(frame, max_edge, t, Corners{vertex(needle, tri[0]), vertex(needle, tri[1]), vertex(needle, tri[2])},
                     alpha, 0, loads);
    }
  build_depth_tables(loads);
  return loads;
}

double post_puncture_load_area(const PostPunctureLoads& loads, double inserted_depth) {
  double total = 0;
  for (const LoadedTriangle& t : loads.triangles) total += clipped_load(t, inserted_depth);
  return total;
}

double post_puncture_force(const PostPunctureLoads& loads, double inserted_depth, double stiffness, double scale) {
  return stiffness * scale * post_puncture_load_area(loads, inserted_depth);  // Eqs 3.18 + 3.20
}

std::vector<double> post_puncture_forces(const PostPunctureLoads& loads, const std::vector<double>& inserted_depths,
                                         double stiffness, double scale) {
  const std::size_t m = inserted_depths.size();
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) { return inserted_depths[i] < inserted_depths[j]; });
  std::vector<double> forces(m, 0.0);
  std::vector<int> active;  // triangles that started before the current depth and may not be complete
  std::size_t next = 0;
  const std::size_t n = loads.triangles.size();
  for (std::size_t s : order) {
    const double h = inserted_depths[s];
    while (next < n && first_depth(loads.triangles[static_cast<std::size_t>(loads.by_first_depth[next])]) < h)
      active.push_back(loads.by_first_depth[next++]);
    // Complete triangles (every vertex strictly above h, as clipped_load counts them) come from the prefix sums.
    const std::size_t complete = static_cast<std::size_t>(
        std::lower_bound(loads.last_depth_sorted.begin(), loads.last_depth_sorted.end(), h) -
        loads.last_depth_sorted.begin());
    double total = loads.full_prefix[complete];
    for (std::size_t i = 0; i < active.size();) {
      const LoadedTriangle& t = loads.triangles[static_cast<std::size_t>(active[i])];
      if (last_depth(t) < h) {  // complete: counted in the prefix sum from now on
        active[i] = active.back();
        active.pop_back();
        continue;
      }
      total += clipped_load(t, h);
      ++i;
    }
    forces[s] = stiffness * scale * total;
  }
  return forces;
}

void validate_force_curve(const ForceDepthCurve& curve, std::string_view what) {
  if (curve.depth.size() != curve.force.size())
    throw InvalidInput(fmt::format("{}: {} depths but {} forces, expected one force per depth", what,
                                   curve.depth.size(), curve.force.size()));
  if (curve.depth.empty()) throw InvalidInput(fmt::format("{}: no samples, expected at least one (depth, force)", what));
  for (std::size_t i = 0; i < curve.depth.size(); ++i) {
    if (!std::isfinite(curve.depth[i]) || !std::isfinite(curve.force[i]))
      throw InvalidInput(fmt::format("{}: sample {} is not finite (depth {}, force {})", what, i + 1, curve.depth[i],
                                     curve.force[i]));
    if (i > 0 && !(curve.depth[i] > curve.depth[i - 1]))
      throw InvalidInput(fmt::format("{}: depth is not monotonic: sample {} has depth {:.6g} m after {:.6g} m, "
                                     "expected strictly increasing depths",
                                     what, i + 1, curve.depth[i], curve.depth[i - 1]));
  }
}

PostPunctureFit fit_post_puncture(const PostPunctureLoads& loads, const ForceDepthCurve& measured,
                                  const PostPunctureFitOptions& options) {
  validate_force_curve(measured, "measured curve");
  if (measured.depth.front() < 0)
    throw InvalidInput(fmt::format("measured curve: depth {:.6g} m is negative, expected inserted depths >= 0",
                                   measured.depth.front()));
  const double fixed = options.fit_stiffness ? options.scale : options.stiffness;
  if (!(fixed > 0) || !std::isfinite(fixed))
    throw InvalidInput(fmt::format("{}: {}, expected a finite value > 0",
                                   options.fit_stiffness ? "scale" : "stiffness", fixed));
  // F = (K·S)·G(depth): linear least squares for the product K·S.
  const std::vector<double> unit = post_puncture_forces(loads, measured.depth, 1.0, 1.0);
  double gg = 0, gf = 0, ff = 0;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    gg += unit[i] * unit[i];
    gf += unit[i] * measured.force[i];
    ff += measured.force[i] * measured.force[i];
  }
  if (!(gg > 0))
    throw InvalidInput("measured curve: the model load is zero at every measured depth (depths of 0?), nothing to fit");
  const double product = gf / gg;
  PostPunctureFit fit;
  fit.samples = static_cast<int>(unit.size());
  fit.stiffness = options.fit_stiffness ? product / options.scale : options.stiffness;
  fit.scale = options.fit_stiffness ? options.scale : product / options.stiffness;
  double rr = 0;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const double r = measured.force[i] - product * unit[i];
    rr += r * r;
  }
  fit.rms_error = std::sqrt(rr / static_cast<double>(unit.size()));
  fit.relative_rms = ff > 0 ? fit.rms_error / std::sqrt(ff / static_cast<double>(unit.size())) : 0;
  return fit;
}

}  // namespace needlekit::insertion
