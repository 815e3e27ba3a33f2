#include "needle_embedding.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>

#include "needle_edge_contact.hpp"  // sharp_feature_points
#include "rigid_surface_distance.hpp"

namespace needlekit::fem::detail {

NeedleEmbedding::NeedleEmbedding(const FunctionSpace& space, const TopSurface& top,
                                   const std::vector<Indenter>& needles, double spacing)
    : space_(space), top_(top) {
  for (const Indenter& needle : needles) {
    const Eigen::Vector3d direction = needle.direction.normalized();
    std::vector<Eigen::Vector3d> points = sharp_feature_points(needle.surface, spacing, 0.0);
    double lowest = -std::numeric_limits<double>::infinity();  // farthest along the direction of motion
    for (const auto& p : points) lowest = std::max(lowest, p.dot(direction));
    std::erase_if(points, [&](const Eigen::Vector3d& p) { return p.dot(direction) < lowest - spacing; });
    needles_.push_back({direction, std::move(points)});
  }
}

double NeedleEmbedding::deepest(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d) const {
  const auto position = [&](int a) -> Eigen::Vector3d { return nodes[a] + u.segment<3>(3 * a); };
  // Distance from p to the deformed top surface (brute force over its faces: once per converged substep).
  const auto surface_distance = [&](const Eigen::Vector3d& p) {
    double nearest = std::numeric_limits<double>::infinity();
    int feature = 0;
    for (const auto& t : top_.triangles) {
      const Eigen::Vector3d a = position(t[0]), b = position(t[1]), c = position(t[2]);
      const Eigen::Vector3d outside = (a.cwiseMin(b).cwiseMin(c) - p).cwiseMax(p - a.cwiseMax(b).cwiseMax(c));
      if (outside.cwiseMax(0.0).squaredNorm() >= nearest) continue;  // its bounding box is farther already
      nearest = std::min(nearest, (p - closest_on_triangle(p, a, b, c, feature)).squaredNorm());
    }
    return std::sqrt(nearest);
  };
  double deepest = 0;
  for (const NeedlePoints& needle : needles_) {
    if (needle.points.empty()) continue;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const auto& p : needle.points) {
      lo = lo.cwiseMin(p + d * needle.direction);
      hi = hi.cwiseMax(p + d * needle.direction);
    }
    for (size_t e = 0; e < space_.elements.size(); ++e) {
      const int* corner = &space_.connectivity[e * static_cast<size_t>(space_.nodes_per_element)];
      std::array<Eigen::Vector3d, 4> x;
      Eigen::Vector3d tlo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), thi = -tlo;
      for (int c = 0; c < 4; ++c) x[c] = position(corner[c]), tlo = tlo.cwiseMin(x[c]), thi = thi.cwiseMax(x[c]);
      if ((thi.array() < lo.array()).any() || (tlo.array() > hi.array()).any()) continue;
      Eigen::Matrix3d edges;
      for (int c = 0; c < 3; ++c) edges.col(c) = x[c + 1] - x[0];
      const Eigen::PartialPivLU<Eigen::Matrix3d> lu(edges);
      for (const auto& point : needle.points) {
        const Eigen::Vector3d p = point + d * needle.direction;
        if ((p.array() < tlo.array()).any() || (p.array() > thi.array()).any()) continue;
        const Eigen::Vector3d l = lu.solve(p - x[0]);
        if (!(l.minCoeff() > 0 && l.sum() < 1)) continue;  // not strictly inside
        deepest = std::max(deepest, surface_distance(p));
      }
    }
  }
  return deepest;
}

}  // namespace needlekit::fem::detail
