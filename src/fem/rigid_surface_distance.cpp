#include "rigid_surface_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace needlekit::fem::detail {

RigidSurfaceDistance::RigidSurfaceDistance(const geometry::TriangleMesh& mesh, const Eigen::Vector3d& direction,
                                           double offset)
    : v_(mesh.vertices), t_(mesh.triangles), offset_(offset) {
  const size_t nt = t_.size();
  face_normal_.resize(nt);
  vertex_normal_.assign(v_.size(), Eigen::Vector3d::Zero());
  edge_normal_.resize(nt);
  tri_lo_.resize(nt);
  tri_hi_.resize(nt);
  std::map<std::pair<int, int>, Eigen::Vector3d> edge_sum;
  lo_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  hi_ = -lo_;
  for (size_t f = 0; f < nt; ++f) {
    const auto& t = t_[f];
    const Eigen::Vector3d n = (v_[t[1]] - v_[t[0]]).cross(v_[t[2]] - v_[t[0]]);
    face_normal_[f] = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
    tri_lo_[f] = v_[t[0]].cwiseMin(v_[t[1]]).cwiseMin(v_[t[2]]);
    tri_hi_[f] = v_[t[0]].cwiseMax(v_[t[1]]).cwiseMax(v_[t[2]]);
    lo_ = lo_.cwiseMin(tri_lo_[f]);
    hi_ = hi_.cwiseMax(tri_hi_[f]);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = (v_[t[(k + 1) % 3]] - v_[t[k]]).normalized();
      const Eigen::Vector3d e2 = (v_[t[(k + 2) % 3]] - v_[t[k]]).normalized();
      const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
      vertex_normal_[t[k]] += angle * face_normal_[f];
      const int a = t[k], b = t[(k + 1) % 3];
      // try_emplace with an explicit zero: Eigen's default constructor leaves a vector uninitialised, so
      // operator[] would add to garbage (which made surface-contact runs differ from run to run).
      edge_sum.try_emplace({std::min(a, b), std::max(a, b)}, Eigen::Vector3d::Zero()).first->second += face_normal_[f];
    }
  }
  lo_.array() -= offset_;
  hi_.array() += offset_;
  const Eigen::Vector3d along = direction.normalized();
  for (size_t f = 0; f < nt; ++f)
    if (face_normal_[f].dot(along) > kLeadingCosine) leading_.push_back(static_cast<int>(f));
  for (auto& n : vertex_normal_)
    if (n.norm() > 0) n.normalize();
  for (size_t f = 0; f < nt; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = t_[f][k], b = t_[f][(k + 1) % 3];
      edge_normal_[f][k] = edge_sum.at({std::min(a, b), std::max(a, b)});
    }
}

Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, int& feature) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) { feature = 0; return a; }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) { feature = 1; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) { feature = 3; return a + d1 / (d1 - d3) * ab; }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) { feature = 2; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) { feature = 5; return a + d2 / (d2 - d6) * ac; }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    feature = 4;
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  feature = 6;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

RigidSurfaceDistance::Nearest RigidSurfaceDistance::nearest(const Eigen::Vector3d& q, double reach,
                                                           const std::vector<int>* subset) const {
  Nearest n;
  n.squared_distance = reach * reach;
  const size_t count = subset ? subset->size() : t_.size();
  for (size_t i = 0; i < count; ++i) {
    const int f = subset ? (*subset)[i] : static_cast<int>(i);
    const Eigen::Vector3d d = (tri_lo_[f] - q).cwiseMax(q - tri_hi_[f]).cwiseMax(0.0);
    if (d.squaredNorm() >= n.squared_distance) continue;
    int feature;
    const auto& t = t_[f];
    const Eigen::Vector3d p = closest_on_triangle(q, v_[t[0]], v_[t[1]], v_[t[2]], feature);
    const double d2 = (q - p).squaredNorm();
    if (d2 < n.squared_distance) {
      n.squared_distance = d2;
      n.triangle = f;
      n.feature = feature;
      n.point = p;
    }
  }
  return n;
}

Eigen::Matrix3d RigidSurfaceDistance::feature_hessian(const Eigen::Vector3d& q, const Nearest& n, double dist,
                                                      double sign) const {
  if (n.feature == 6 || !(dist > 0.5 * offset_) || offset_ == 0) return Eigen::Matrix3d::Zero();
  const Eigen::Vector3d normal = (q - n.point) / dist;
  Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - normal * normal.transpose();
  if (n.feature >= 3) {  // edges 3: corners 0-1, 4: 1-2, 5: 2-0
    const auto& t = t_[static_cast<size_t>(n.triangle)];
    const int k = n.feature - 3;
    const Eigen::Vector3d along = (v_[t[(k + 1) % 3]] - v_[t[k]]).normalized();
    across -= along * along.transpose();
  }
  return sign / dist * across;
}

SignedDistance RigidSurfaceDistance::signed_distance(const Eigen::Vector3d& q, double reach, bool ahead) const {
  const Nearest all = nearest(q, reach + offset_, nullptr);
  const double best = all.squared_distance;
  const int best_f = all.triangle, best_feature = all.feature;
  const Eigen::Vector3d best_p = all.point;
  SignedDistance out;
  if (best_f < 0) {
    out.distance = reach;
    out.normal.setZero();
    return out;
  }
  Eigen::Vector3d pseudo;
  if (best_feature < 3) pseudo = vertex_normal_[t_[best_f][best_feature]];
  else if (best_feature < 6) {
    // edges 3: (a,b) = corner 0-1; 4: (b,c) = 1-2; 5: (a,c) = edge 2-0
    const int k = best_feature == 3 ? 0 : best_feature == 4 ? 1 : 2;
    pseudo = edge_normal_[best_f][k];
  } else pseudo = face_normal_[best_f];
  const double dist = std::sqrt(best);
  const Eigen::Vector3d diff = q - best_p;
  const bool inside = diff.dot(pseudo) < 0;
  if (inside && ahead && !leading_.empty()) {
    // The nearest point of the leading faces (see the header): the node leaves the needle the way the needle's
    // motion pushes it.
    const Nearest lead = nearest(q, std::numeric_limits<double>::infinity(), &leading_);
    const double lead_dist = std::sqrt(lead.squared_distance);
    out.distance = -lead_dist - offset_;
    out.normal = lead_dist > 1e-12 * (hi_ - lo_).norm() ? Eigen::Vector3d((lead.point - q) / lead_dist)
                                                        : face_normal_[lead.triangle];
    out.hessian = feature_hessian(q, lead, lead_dist, -1);
    return out;
  }
  out.distance = (inside ? -dist : dist) - offset_;
  if (dist > 1e-12 * (hi_ - lo_).norm()) {
    out.normal = inside ? Eigen::Vector3d(-diff / dist) : Eigen::Vector3d(diff / dist);
    out.hessian = feature_hessian(q, all, dist, inside ? -1 : 1);
  } else {
    out.normal = pseudo.normalized();
  }
  return out;
}

}  // namespace needlekit::fem::detail
