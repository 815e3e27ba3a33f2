#include "surface_contact.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace needlekit::fem::detail {

SurfaceContact::SurfaceContact(const TopSurface& top, const FunctionSpace& space, const std::vector<Indenter>& needles,
                               const SolverOptions& options)
    : top_nodes_(top.nodes), friction_(options.friction) {
  h_min_ = std::numeric_limits<double>::infinity();
  stiffness_.resize(top.nodes.size());
  for (size_t t = 0; t < top.nodes.size(); ++t) {
    const int n = top.nodes[t];
    h_min_ = std::min(h_min_, top.node_size[n]);
    stiffness_[t] = options.penalty_factor * space.node_youngs_modulus[n] / top.node_size[n] * top.node_area[n];
  }
  const size_t count = top.nodes.size();
  at_rest_.resize(count);  // the slip counts from the reference positions, the needle at d = 0
  for (size_t t = 0; t < count; ++t) at_rest_[t].reference = space.nodes[top.nodes[t]];
  for (const Indenter& needle : needles) {
    const Eigen::Vector3d direction = needle.direction.normalized();
    needles_.push_back(NeedleContact{
        direction, std::make_unique<RigidSurfaceDistance>(needle.surface, direction, needle.edge_radius),
        std::vector<double>(count, 0.0), std::vector<double>(count, std::numeric_limits<double>::infinity()),
        std::vector<double>(count, 0.0), std::vector<Eigen::Vector3d>(count, Eigen::Vector3d::Zero()),
        std::vector<Eigen::Vector3d>(count, Eigen::Vector3d::Zero()),
        std::vector<char>(count, 1),  // the needle starts above the tissue
        at_rest_, std::vector<Eigen::Vector3d>(count, Eigen::Vector3d::Zero()),
        NeedleEdgeContact(top, stiffness_,
                          options.two_pass ? sharp_feature_points(needle.surface, h_min_ / 2, needle.edge_radius)
                                   : std::vector<Eigen::Vector3d>{},
                          direction)});
  }
}

double SurfaceContact::evaluate(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d,
                                bool want_force, bool want_tangent, Eigen::VectorXd& force,
                                const std::vector<int>& free_index, const UpperPattern& pattern,
                                std::vector<double>& values) {
  if (want_force) force.setZero(u.size());
  double energy = 0;
  for (auto& nd : needles_) {
    const double reach = (nd.distance->box_max() - nd.distance->box_min()).norm();
    double margin = 0;
    for (size_t t = 0; t < top_nodes_.size(); ++t) margin = std::max(margin, nd.lambda[t] / stiffness_[t]);
    margin += 1e-9 * reach;
    const Eigen::Vector3d lo = nd.distance->box_min().array() - margin, hi = nd.distance->box_max().array() + margin;
    for (size_t t = 0; t < top_nodes_.size(); ++t) {
      const int a = top_nodes_[t];
      const double k = stiffness_[t];
      const Eigen::Vector3d q = relative(nodes, u, d, nd, t);
      nd.position_now[t] = q;
      nd.force_now[t] = 0;
      nd.gap_now[t] = std::numeric_limits<double>::infinity();
      if (friction_ > 0) {  // the frozen Coulomb law (coulomb_friction.hpp); zero where the bound is
        const FrictionResponse fr = friction_response(nd.friction[t], q, k);
        nd.traction_now[t] = fr.force;
        energy += fr.energy;
        if (want_force) force.segment<3>(3 * a) -= fr.force;
        if (want_tangent && nd.friction[t].bound > 0)
          add_node_block<1>({a}, fr.stiffness, free_index, pattern, values);
      }
      if ((q.array() < lo.array()).any() || (q.array() > hi.array()).any()) continue;
      const auto sd = nd.distance->signed_distance(q, reach, nd.ahead[t]);
      nd.gap_now[t] = sd.distance;
      const double p = nd.lambda[t] - k * sd.distance;
      if (p <= 0) continue;
      energy += p * p / (2 * k);
      nd.force_now[t] = p;
      nd.normal_now[t] = sd.normal;
      if (want_force) force.segment<3>(3 * a) += p * sd.normal;
      if (want_tangent) {  // the exact k n n^T - P hess g; n turns as a node slides round a rounded edge
        Eigen::Matrix3d curvature = -p * sd.hessian;
        if (positive_curvature_) curvature = positive_part<3>(curvature);
        add_node_block<1>({a}, Eigen::Matrix3d(k * sd.normal * sd.normal.transpose() + curvature), free_index,
                          pattern, values);
      }
    }
    energy += nd.edges.evaluate(nodes, u, d, want_force, want_tangent, force, free_index, pattern, values);
  }
  return energy;
}

double SurfaceContact::max_penetration() const {
  double pen = 0;
  for (const auto& nd : needles_) {
    for (double gap : nd.gap_now)
      if (std::isfinite(gap)) pen = std::max(pen, -gap);
    pen = std::max(pen, nd.edges.max_penetration());
  }
  return pen;
}

void SurfaceContact::augment() {
  for (auto& nd : needles_) {
    nd.lambda = nd.force_now;
    nd.edges.augment();
    if (friction_ == 0) continue;
    for (size_t t = 0; t < top_nodes_.size(); ++t) {
      nd.friction[t].bound = friction_ * nd.force_now[t];
      if (nd.force_now[t] > 0) nd.friction[t].normal = nd.normal_now[t];
    }
  }
}

bool SurfaceContact::friction_settled() const {
  if (friction_ == 0) return true;
  double largest = 0, change = 0;
  for (const auto& nd : needles_)
    for (size_t t = 0; t < top_nodes_.size(); ++t) {
      largest = std::max(largest, friction_ * nd.force_now[t]);
      change = std::max(change, std::abs(friction_ * nd.force_now[t] - nd.friction[t].bound));
    }
  return change <= kFrictionBoundTolerance * largest;
}

void SurfaceContact::commit_friction(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d) {
  if (friction_ == 0) return;
  for (auto& nd : needles_)
    for (size_t t = 0; t < top_nodes_.size(); ++t) {
      FrictionState& state = nd.friction[t];
      const Eigen::Vector3d q = relative(nodes, u, d, nd, t);
      state.traction = friction_response(state, q, stiffness_[t]).force;
      state.reference = q;
    }
}

Eigen::Vector3d SurfaceContact::force_on_needle(size_t needle) const {
  const NeedleContact& nd = needles_[needle];
  Eigen::Vector3d sum = nd.edges.force_on_needle();
  for (size_t t = 0; t < top_nodes_.size(); ++t) sum += nd.traction_now[t] - nd.force_now[t] * nd.normal_now[t];
  return sum;
}

Eigen::Vector3d SurfaceContact::moment_on_needle(size_t needle) const {
  const NeedleContact& nd = needles_[needle];
  Eigen::Vector3d sum = nd.edges.moment_on_needle();
  for (size_t t = 0; t < top_nodes_.size(); ++t)
    sum += nd.position_now[t].cross(nd.traction_now[t] - nd.force_now[t] * nd.normal_now[t]);
  return sum;
}

void SurfaceContact::update_ahead(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d) {
  for (auto& nd : needles_) {
    const double reach = (nd.distance->box_max() - nd.distance->box_min()).norm();
    for (size_t t = 0; t < top_nodes_.size(); ++t) {
      const auto sd = nd.distance->signed_distance(relative(nodes, u, d, nd, t), reach);
      nd.ahead[t] = sd.distance >= reach || sd.normal.dot(nd.direction) > RigidSurfaceDistance::kLeadingCosine;
    }
    nd.edges.keep_pairs(nodes, u, d);
  }
}

void SurfaceContact::forget_history() {
  for (auto& nd : needles_) {
    std::fill(nd.lambda.begin(), nd.lambda.end(), 0.0);
    nd.edges.set_multipliers({});
    nd.edges.drop_kept_pairs();
    nd.friction = at_rest_;
  }
}

SurfaceContact::Multipliers SurfaceContact::multipliers() const {
  Multipliers out;
  for (const auto& nd : needles_) {
    out.nodes.push_back(nd.lambda);
    out.edges.push_back(nd.edges.multipliers());
    out.friction.push_back(nd.friction);
  }
  return out;
}

void SurfaceContact::set_multipliers(const Multipliers& multipliers) {
  for (size_t k = 0; k < needles_.size(); ++k) {
    needles_[k].lambda = multipliers.nodes[k];
    needles_[k].edges.set_multipliers(multipliers.edges[k]);
    needles_[k].friction = multipliers.friction[k];
  }
}

size_t SurfaceContact::active_set_fingerprint() const {
  size_t hash = 1469598103934665603ull;  // FNV-1a over the indices of the active (needle, node) pairs
  for (size_t k = 0; k < needles_.size(); ++k) {
    for (size_t t = 0; t < top_nodes_.size(); ++t)
      if (needles_[k].force_now[t] > 0) hash = (hash ^ (k * top_nodes_.size() + t)) * 1099511628211ull;
    needles_[k].edges.hash_active(hash);
  }
  return hash;
}

}  // namespace needlekit::fem::detail
