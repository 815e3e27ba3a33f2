#include "surface_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace needlekit::fem::detail {

SurfaceContact::SurfaceContact(const TopSurface& top, const FunctionSpace& space, const std::vector<Indenter>& needles,
                               double penalty_factor)
    : top_nodes_(top.nodes) {
  h_min_ = std::numeric_limits<double>::infinity();
  stiffness_.resize(top.nodes.size());
  for (size_t t = 0; t < top.nodes.size(); ++t) {
    const int n = top.nodes[t];
    h_min_ = std::min(h_min_, top.node_size[n]);
    stiffness_[t] = penalty_factor * space.node_youngs_modulus[n] / top.node_size[n] * top.node_area[n];
  }
  for (const Indenter& needle : needles) {
    NeedleContact nc;
    nc.direction = needle.direction.normalized();
    nc.distance = std::make_unique<RigidSurfaceDistance>(needle.surface, nc.direction, needle.edge_radius);
    nc.lambda.assign(top.nodes.size(), 0.0);
    nc.gap_now.assign(top.nodes.size(), std::numeric_limits<double>::infinity());
    nc.force_now.assign(top.nodes.size(), 0.0);
    nc.normal_now.assign(top.nodes.size(), Eigen::Vector3d::Zero());
    nc.ahead.assign(top.nodes.size(), 1);  // the needle starts above the tissue
    needles_.push_back(std::move(nc));
  }
}

double SurfaceContact::evaluate(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d,
                                bool want_force, bool want_tangent, Eigen::VectorXd& force,
                                const std::vector<int>& free_index, const UpperPattern& pattern,
                                std::vector<double>& values) {
  if (want_force) force.setZero(u.size());
  double energy = 0;
  for (auto& nd : needles_) {
    const Eigen::Vector3d shift = d * nd.direction;
    const double reach = (nd.distance->box_max() - nd.distance->box_min()).norm();
    double margin = 0;
    for (size_t t = 0; t < top_nodes_.size(); ++t) margin = std::max(margin, nd.lambda[t] / stiffness_[t]);
    margin += 1e-9 * reach;
    const Eigen::Vector3d lo = nd.distance->box_min().array() - margin, hi = nd.distance->box_max().array() + margin;
    for (size_t t = 0; t < top_nodes_.size(); ++t) {
      const int a = top_nodes_[t];
      const double k = stiffness_[t];
      const Eigen::Vector3d q = nodes[a] + u.segment<3>(3 * a) - shift;
      nd.force_now[t] = 0;
      nd.gap_now[t] = std::numeric_limits<double>::infinity();
      if ((q.array() < lo.array()).any() || (q.array() > hi.array()).any()) continue;
      const auto sd = nd.distance->signed_distance(q, reach, nd.ahead[t]);
      nd.gap_now[t] = sd.distance;
      const double p = nd.lambda[t] - k * sd.distance;
      if (p <= 0) continue;
      energy += p * p / (2 * k);
      nd.force_now[t] = p;
      nd.normal_now[t] = sd.normal;
      if (want_force) force.segment<3>(3 * a) += p * sd.normal;
      if (!want_tangent) continue;
      const Eigen::Matrix3d kn = k * sd.normal * sd.normal.transpose();
      for (int i = 0; i < 3; ++i) {
        const int r = free_index[3 * a + i];
        if (r < 0) continue;
        for (int j = 0; j < 3; ++j) {
          const int c = free_index[3 * a + j];
          if (c < 0 || r > c) continue;
          values[static_cast<size_t>(entry_position(pattern, r, c))] += kn(i, j);
        }
      }
    }
  }
  return energy;
}

double SurfaceContact::max_penetration() const {
  double pen = 0;
  for (const auto& nd : needles_)
    for (double gap : nd.gap_now)
      if (std::isfinite(gap)) pen = std::max(pen, -gap);
  return pen;
}

void SurfaceContact::augment() {
  for (auto& nd : needles_) nd.lambda = nd.force_now;
}

void SurfaceContact::update_ahead(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d) {
  for (auto& nd : needles_) {
    const double reach = (nd.distance->box_max() - nd.distance->box_min()).norm();
    for (size_t t = 0; t < top_nodes_.size(); ++t) {
      const int a = top_nodes_[t];
      const auto sd = nd.distance->signed_distance(nodes[a] + u.segment<3>(3 * a) - d * nd.direction, reach);
      nd.ahead[t] = sd.distance >= reach || sd.normal.dot(nd.direction) > RigidSurfaceDistance::kLeadingCosine;
    }
  }
}

std::vector<std::vector<double>> SurfaceContact::multipliers() const {
  std::vector<std::vector<double>> out;
  for (const auto& nd : needles_) out.push_back(nd.lambda);
  return out;
}

void SurfaceContact::set_multipliers(const std::vector<std::vector<double>>& multipliers) {
  for (size_t k = 0; k < needles_.size(); ++k) needles_[k].lambda = multipliers[k];
}

size_t SurfaceContact::active_set_fingerprint() const {
  size_t hash = 1469598103934665603ull;  // FNV-1a over the indices of the active (needle, node) pairs
  for (size_t k = 0; k < needles_.size(); ++k)
    for (size_t t = 0; t < top_nodes_.size(); ++t)
      if (needles_[k].force_now[t] > 0) hash = (hash ^ (k * top_nodes_.size() + t)) * 1099511628211ull;
  return hash;
}

}  // namespace needlekit::fem::detail
