#include "needlekit/patch/flexible_fit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>

#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/cutting_plane_trace.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"
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

}  // namespace

FittedPatch flexible_fit(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                         const FlexibleFitOptions& options) {
  if (!(options.max_spring_energy > 0)) {
    throw InvalidInput(fmt::format("patch.max_spring_energy: {:.6g} mJ is not positive, expected an energy > 0",
                                   options.max_spring_energy * 1e3));
  }
  if (options.cap_samples < 2 || options.cap_samples > 10000) {
    throw InvalidInput(fmt::format("cap_samples: {} is out of range, expected [2, 10000]", options.cap_samples));
  }
  const int n = design.node_count();
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
  const Eigen::Vector3d first_point = hit->point;
  fit.first_node = first;
  fit.affected_nodes.clear();
  fit.status = FitStatus::Ok;
  fit.reason.clear();

  // The springs at every node.
  std::vector<std::vector<int>> springs_at(n);
  for (std::size_t s = 0; s < design.springs.size(); ++s) {
    springs_at[design.springs[s].a].push_back(static_cast<int>(s));
    springs_at[design.springs[s].b].push_back(static_cast<int>(s));
  }
  auto offset = [&](int from, int to) -> Eigen::Vector3d {
    const Eigen::Vector2d d = design.rest_positions[to] - design.rest_positions[from];
    return d.x() * frame.u + d.y() * frame.v;
  };

  std::vector<Eigen::Vector3d> position(n), tangent_u(n), tangent_v(n);
  std::vector<geometry::SurfaceLocation> location(n);
  std::vector<bool> mapped(n, false), on_surface(n, false);
  std::vector<int> boundary_nodes, degenerate_nodes, capped_nodes;
  {
    const geometry::ClosestPoint cp = surface.closest_point(first_point);
    position[first] = cp.point;
    location[first] = geometry::surface_location(cp);
    mapped[first] = on_surface[first] = true;
    // The patch frame turned onto the tangent plane at the first node.
    const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(-frame.approach, surface.face_normal(cp.triangle));
    tangent_u[first] = turn * frame.u;
    tangent_v[first] = turn * frame.v;
  }
  const double length_scale = design.width_u + design.width_v;
  std::deque<int> active{first};  // Alg 5.1: ActiveNodeList
  while (!active.empty()) {
    const int a = active.front();
    active.pop_front();
    for (const int k : neighbors(design, a)) {
      if (mapped[k]) continue;
      // Alg 5.2 / §5.7.2: walk the rest length along the original direction (Alg 5.3).
      const Eigen::Vector3d d = offset(a, k);
      // The spring's direction in the active node's tangent frame: the patch's (U, V) frame carried from node to node
      // by the minimal rotation between successive surface normals (discrete parallel transport), so that the
      // eight directions keep their angles on a tilted or curved surface. The cutting plane contains this direction
      // and the surface normal (Alg 5.3; notes).
      const Eigen::Vector2d rest = design.rest_positions[k] - design.rest_positions[a];
      const Eigen::Vector3d turned = rest.x() * tangent_u[a] + rest.y() * tangent_v[a];
      const geometry::SurfacePath walk = walk_on(surface, location[a], turned, d.norm(), options.walk);
      {
        const Eigen::Quaterniond carry = Eigen::Quaterniond::FromTwoVectors(
            surface.face_normal(location[a].triangle), surface.face_normal(walk.end.triangle));
        tangent_u[k] = carry * tangent_u[a];
        tangent_v[k] = carry * tangent_v[a];
      }
      if (walk.status == geometry::PathStatus::HitBoundary) boundary_nodes.push_back(k);
      if (walk.status == geometry::PathStatus::DegenerateTriangle || walk.status == geometry::PathStatus::StepLimit) {
        degenerate_nodes.push_back(k);
      }
      const Eigen::Vector3d conforming = walk.end_point;  // N_int
      const Eigen::Vector3d rigid = position[a] + d;   // N: the patch locally undeformed
      // The energy cap: the largest λ with every spring to a mapped node at or under E_cri (Eqs 5.13, 5.14).
      auto worst_energy = [&](double lambda) {
        const Eigen::Vector3d x = rigid + lambda * (conforming - rigid);
        double worst = 0;
        for (const int s : springs_at[k]) {
          const Spring& spring = design.springs[s];
          const int other = spring.a == k ? spring.b : spring.a;
          if (!mapped[other]) continue;
          const double stretch = (x - position[other]).norm() - spring.rest_length;
          worst = std::max(worst, 0.5 * spring.stiffness * stretch * stretch);
        }
        return worst;
      };
      double lambda = 1;
      if (worst_energy(1) > options.max_spring_energy) {
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
          lambda = static_cast<double>(least_sample) / samples;
          capped_nodes.push_back(k);
        } else {
          double lo = static_cast<double>(best_feasible) / samples, hi = lo + 1.0 / samples;
          for (int it = 0; it < 40; ++it) {
            const double mid = 0.5 * (lo + hi);
            (worst_energy(mid) <= options.max_spring_energy ? lo : hi) = mid;
          }
          lambda = lo;
        }
      }
      Eigen::Vector3d x = rigid + lambda * (conforming - rigid);
      bool touching = lambda >= 1;
      if (!touching) {  // the surface is impenetrable: a node beneath it goes back onto it
        const geometry::ClosestPoint cp = surface.closest_point(x);
        const Eigen::Vector3d normal = surface.interpolated_normal(cp.triangle, cp.barycentric);
        if ((x - cp.point).dot(normal) < 0) {
          x = cp.point;
          touching = true;
        }
      }
      position[k] = x;
      on_surface[k] = touching || (x - conforming).norm() <= 1e-9 * length_scale;
      location[k] = walk.end;
      mapped[k] = true;
      active.push_back(k);
    }
  }
  fit.positions = position;
  fit.on_surface = on_surface;
  fit.normals = grid_normals(design, position, frame.approach);
  auto name = [](const std::vector<int>& nodes) { return fmt::format("{}", fmt::join(nodes, ", ")); };
  std::vector<std::string> reasons;
  if (!capped_nodes.empty()) {
    fit.status = FitStatus::EnergyCapExceeded;
    fit.affected_nodes = capped_nodes;
    reasons.push_back(fmt::format("springs at {} node(s) exceed E_cri even undeformed: nodes {}", capped_nodes.size(),
                                  name(capped_nodes)));
  }
  if (!degenerate_nodes.empty()) {
    fit.status = FitStatus::DegenerateSurface;
    fit.affected_nodes = degenerate_nodes;
    reasons.push_back(fmt::format("traverses stopped at a degenerate triangle for {} node(s): nodes {}",
                                  degenerate_nodes.size(), name(degenerate_nodes)));
  }
  if (!boundary_nodes.empty()) {
    fit.status = FitStatus::BoundaryReached;
    fit.affected_nodes = boundary_nodes;
    reasons.push_back(fmt::format("traverses reached the surface's boundary for {} node(s) (the patch is larger than "
                                  "the reachable surface): nodes {}",
                                  boundary_nodes.size(), name(boundary_nodes)));
  }
  fit.reason = fmt::format("{}", fmt::join(reasons, "; "));
  return fit;
}

}  // namespace needlekit::patch
