#include "needlekit/patch/flexible_fit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/geometry/cutting_plane_trace.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"
#include "needlekit/patch/fit_parameters.hpp"
#include "needlekit/patch/rigid_fit.hpp"

namespace needlekit::patch {
namespace {

// Alg 5.3 by the surface's traces: the cutting plane (dissertation) or the straightest geodesic (unfolding).
geometry::SurfacePath walk_on(const geometry::SurfaceMesh& surface, const geometry::SurfaceLocation& start,
                              const Eigen::Vector3d& direction, double length, WalkMethod method) {
  try {
    return method == WalkMethod::CuttingPlane ? geometry::cutting_plane_trace(surface, start, direction, length)
                                              : geometry::straightest_geodesic(surface, start, direction, length);
  } catch (const InvalidInput& error) {  // e.g. a direction along the normal of a degenerate start triangle
    geometry::SurfacePath path;
    path.status = geometry::PathStatus::DegenerateTriangle;
    path.reason = error.what();
    path.end = start;
    path.end_point = geometry::position(surface, start);
    return path;
  }
}

void validate(const FlexibleFitOptions& options) { check_ranges(kFlexibleFitParameters, options, "patch"); }

// The energy cap (Eqs 5.13, 5.14): the largest λ in [0, 1] with worst_energy(λ) <= E_cri, by sampling from λ = 1 down
// and bisecting the last step; when no sample is feasible, the sample of least energy and `capped` set.
template <class WorstEnergy>
double capped_lambda(const WorstEnergy& worst_energy, const FlexibleFitOptions& options, bool& capped) {
  capped = false;
  if (worst_energy(1) <= options.max_spring_energy) return 1;
  const int samples = options.cap_samples;
  int best_feasible = -1;
  int least_sample = 0;
  double least = std::numeric_limits<double>::infinity();
  for (int i = samples; i >= 0; --i) {
    const double e = worst_energy(static_cast<double>(i) / samples);
    if (e <= options.max_spring_energy) {
      best_feasible = i;
      break;
    }
    if (e < least) {
      least = e;
      least_sample = i;
    }
  }
  if (best_feasible < 0) {
    capped = true;
    return static_cast<double>(least_sample) / samples;
  }
  double lo = static_cast<double>(best_feasible) / samples, hi = lo + 1.0 / samples;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (worst_energy(mid) <= options.max_spring_energy ? lo : hi) = mid;
  }
  return lo;
}

// Alg 5.1's breadth-first mapping of the patch's nodes onto the surface from the first node, each node placed by
// Alg 5.2 (a walk of the spring's rest length, Alg 5.3) and held back by the energy cap.
class NodeMapping {
public:
  NodeMapping(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
              const FlexibleFitOptions& options)
      : surface_(surface), design_(design), frame_(frame), options_(options) {
    const std::size_t n = static_cast<std::size_t>(design.node_count());
    springs_at_.resize(n);
    for (std::size_t s = 0; s < design.springs.size(); ++s) {
      springs_at_[design.springs[s].a].push_back(static_cast<int>(s));
      springs_at_[design.springs[s].b].push_back(static_cast<int>(s));
    }
    position_.resize(n);
    tangent_u_.resize(n);
    tangent_v_.resize(n);
    location_.resize(n);
    mapped_.assign(n, false);
    on_surface_.assign(n, false);
  }

  void run(int first, const Eigen::Vector3d& first_point) {
    const geometry::ClosestPoint cp = surface_.closest_point(first_point);
    position_[first] = cp.point;
    location_[first] = geometry::surface_location(cp);
    mapped_[first] = on_surface_[first] = true;
    // The patch frame turned onto the tangent plane at the first node.
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond::FromTwoVectors(-frame_.approach, surface_.face_normal(cp.triangle));
    tangent_u_[first] = turn * frame_.u;
    tangent_v_[first] = turn * frame_.v;
    std::deque<int> active{first};  // Alg 5.1: ActiveNodeList
    while (!active.empty()) {
      const int a = active.front();
      active.pop_front();
      for (const int k : neighbors(design_, a)) {
        if (mapped_[k]) continue;
        map_node(a, k);
        active.push_back(k);
        report_progress();
      }
    }
  }

  // The fit's positions, contact flags and normals, and its status from the nodes that met trouble.
  void finish(FittedPatch& fit) const {
    fit.positions = position_;
    fit.on_surface = on_surface_;
    fit.normals = grid_normals(design_, position_, frame_.approach);
    auto name = [](const std::vector<int>& nodes) { return fmt::format("{}", fmt::join(nodes, ", ")); };
    std::vector<std::string> reasons;
    if (!capped_nodes_.empty()) {
      fit.status = FitStatus::EnergyCapExceeded;
      fit.affected_nodes = capped_nodes_;
      reasons.push_back(fmt::format("springs at {} node(s) exceed E_cri even undeformed: nodes {}",
                                    capped_nodes_.size(), name(capped_nodes_)));
    }
    if (!degenerate_nodes_.empty()) {
      fit.status = FitStatus::DegenerateSurface;
      fit.affected_nodes = degenerate_nodes_;
      reasons.push_back(fmt::format("traverses stopped at a degenerate triangle for {} node(s): nodes {}",
                                    degenerate_nodes_.size(), name(degenerate_nodes_)));
    }
    if (!boundary_nodes_.empty()) {
      fit.status = FitStatus::BoundaryReached;
      fit.affected_nodes = boundary_nodes_;
      reasons.push_back(fmt::format("traverses reached the surface's boundary for {} node(s) (the patch is larger "
                                    "than the reachable surface): nodes {}",
                                    boundary_nodes_.size(), name(boundary_nodes_)));
    }
    fit.reason = fmt::format("{}", fmt::join(reasons, "; "));
  }

private:
  // options.progress with the fraction of nodes mapped; Interrupted when it returns false.
  void report_progress() {
    ++mapped_count_;
    if (options_.progress && !options_.progress(static_cast<double>(mapped_count_) / design_.node_count())) {
      throw Interrupted();
    }
  }

  // Alg 5.2 / §5.7.2: node k from its mapped neighbour a, walking the rest length along the original direction.
  void map_node(int a, int k) {
    const Eigen::Vector2d rest = design_.rest_positions[k] - design_.rest_positions[a];
    const Eigen::Vector3d d = rest.x() * frame_.u + rest.y() * frame_.v;
    // The spring's direction in the active node's tangent frame: the patch's (U, V) frame carried from node to node
    // by the minimal rotation between successive surface normals (discrete parallel transport), so that the eight
    // directions keep their angles on a tilted or curved surface. The cutting plane contains this direction and the
    // surface normal (Alg 5.3; notes).
    const Eigen::Vector3d turned = rest.x() * tangent_u_[a] + rest.y() * tangent_v_[a];
    const geometry::SurfacePath walk = walk_on(surface_, location_[a], turned, d.norm(), options_.walk);
    const Eigen::Quaterniond carry = Eigen::Quaterniond::FromTwoVectors(surface_.face_normal(location_[a].triangle),
                                                                        surface_.face_normal(walk.end.triangle));
    tangent_u_[k] = carry * tangent_u_[a];
    tangent_v_[k] = carry * tangent_v_[a];
    if (walk.status == geometry::PathStatus::HitBoundary) boundary_nodes_.push_back(k);
    if (walk.status == geometry::PathStatus::DegenerateTriangle || walk.status == geometry::PathStatus::StepLimit) {
      degenerate_nodes_.push_back(k);
    }
    const Eigen::Vector3d conforming = walk.end_point;  // N_int
    const Eigen::Vector3d rigid = position_[a] + d;     // N: the patch locally undeformed
    // The worst energy of the springs from node k to mapped nodes with k at rigid + λ (conforming − rigid).
    auto worst_energy = [&](double lambda) {
      const Eigen::Vector3d x = rigid + lambda * (conforming - rigid);
      double worst = 0;
      for (const int s : springs_at_[k]) {
        const Spring& spring = design_.springs[s];
        const int other = spring.a == k ? spring.b : spring.a;
        if (!mapped_[other]) continue;
        const double stretch = (x - position_[other]).norm() - spring.rest_length;
        worst = std::max(worst, 0.5 * spring.stiffness * stretch * stretch);
      }
      return worst;
    };
    bool capped = false;
    const double lambda = capped_lambda(worst_energy, options_, capped);
    if (capped) capped_nodes_.push_back(k);
    Eigen::Vector3d x = rigid + lambda * (conforming - rigid);
    bool touching = lambda >= 1;
    if (!touching) {  // the surface is impenetrable: a node beneath it goes back onto it
      const geometry::ClosestPoint cp = surface_.closest_point(x);
      const Eigen::Vector3d normal = surface_.interpolated_normal(cp.triangle, cp.barycentric);
      if ((x - cp.point).dot(normal) < 0) {
        x = cp.point;
        touching = true;
      }
    }
    const double length_scale = design_.width_u + design_.width_v;
    position_[k] = x;
    on_surface_[k] = touching || (x - conforming).norm() <= 1e-9 * length_scale;
    location_[k] = walk.end;
    mapped_[k] = true;
  }

  const geometry::SurfaceMesh& surface_;
  const PatchDesign& design_;
  const PatchFrame& frame_;
  const FlexibleFitOptions& options_;
  std::vector<std::vector<int>> springs_at_;  // the springs at every node
  std::vector<Eigen::Vector3d> position_, tangent_u_, tangent_v_;
  std::vector<geometry::SurfaceLocation> location_;
  std::vector<bool> mapped_, on_surface_;
  std::vector<int> boundary_nodes_, degenerate_nodes_, capped_nodes_;
  int mapped_count_ = 1;  // the first node
};

}  // namespace

FittedPatch flexible_fit(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                         const FlexibleFitOptions& options) {
  validate(options);
  // The first node: the rigid patch's first contact, or the corner N(0,0) projected along the approach.
  FittedPatch fit = rigid_fit(surface, design, frame);
  if (fit.status == FitStatus::MissesSurface) return fit;
  const std::vector<Eigen::Vector3d> start = flat_positions(design, frame, frame.approach_height);
  const int first = options.first_node == FirstNode::Corner ? design.node(0, 0) : fit.first_node;
  const auto hit = surface.first_hit(start[first], frame.approach);  // Alg 5.1: project the first node
  if (!hit) {
    fit.status = FitStatus::MissesSurface;
    fit.reason = "the first node N(0,0) is not over the surface along the approach direction: node 0";
    fit.affected_nodes = {first};
    return fit;
  }
  fit.first_node = first;
  fit.affected_nodes.clear();
  fit.status = FitStatus::Ok;
  fit.reason.clear();
  NodeMapping mapping(surface, design, frame, options);
  mapping.run(first, hit->point);
  mapping.finish(fit);
  return fit;
}

}  // namespace needlekit::patch
