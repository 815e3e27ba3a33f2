#include "needle_edge_contact.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace needlekit::fem::detail {

namespace {
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {  // [v]x w = v x w
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// The gap and the projection's coordinates only (the search); `valid` false for a degenerate triangle.
struct Projection {
  bool valid = false;
  double gap = 0;
  double xi1 = 0, xi2 = 0;
  // Within the triangle widened by `margin`.
  bool over(double margin = kMargin) const {
    return valid && xi1 >= -margin && xi2 >= -margin && xi1 + xi2 <= 1 + margin;
  }
};
Projection project(const Eigen::Vector3d& p, const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                   const Eigen::Vector3d& x2) {
  const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0, r = p - x0, m = e1.cross(e2);
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2), det = g11 * g22 - g12 * g12;
  Projection out;
  if (!(m.norm() > 0) || !(det > 0)) return out;
  const double b1 = e1.dot(r), b2 = e2.dot(r);
  out.valid = true;
  out.gap = r.dot(m) / m.norm();
  out.xi1 = (g22 * b1 - g12 * b2) / det;
  out.xi2 = (g11 * b2 - g12 * b1) / det;
  return out;
}
}  // namespace

PlaneGap triangle_plane_gap(const Eigen::Vector3d& p, const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                            const Eigen::Vector3d& x2) {
  const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0, r = p - x0, m = e1.cross(e2);
  const double length = m.norm();
  PlaneGap out;
  out.normal = m / length;
  const Eigen::Vector3d& n = out.normal;
  out.gap = r.dot(n);
  Eigen::Matrix2d gram;
  gram << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
  const Eigen::Matrix2d inverse = gram.inverse();
  const Eigen::Vector2d xi = inverse * Eigen::Vector2d(e1.dot(r), e2.dot(r));
  out.weights = {1 - xi[0] - xi[1], xi[0], xi[1]};
  for (int i = 0; i < 3; ++i) out.gradient.segment<3>(3 * i) = -out.weights[i] * n;  // dg/dx_i = -N_i n
  // dn/dx_j (n = m/|m|, dm = de1 x e2 + e1 x de2) and dxi/dx_j (xi = G^-1 [e1.r, e2.r], G the Gram matrix of e1,
  // e2): the derivatives of dg/dx_i = -N_i n.
  const Eigen::Matrix3d plane = (Eigen::Matrix3d::Identity() - n * n.transpose()) / length;
  std::array<Eigen::Matrix3d, 3> dn;
  dn[1] = -plane * cross_matrix(e2);
  dn[2] = plane * cross_matrix(e1);
  dn[0] = -(dn[1] + dn[2]);
  const Eigen::Vector3d normal_part = out.gap * n;  // r - xi1 e1 - xi2 e2
  Eigen::Matrix<double, 2, 3> c1, c2, cr;
  c1.row(0) = (normal_part - xi[0] * e1).transpose();
  c1.row(1) = (-xi[0] * e2).transpose();
  c2.row(0) = (-xi[1] * e1).transpose();
  c2.row(1) = (normal_part - xi[1] * e2).transpose();
  cr.row(0) = e1.transpose();
  cr.row(1) = e2.transpose();
  std::array<Eigen::Matrix<double, 2, 3>, 3> dxi{inverse * (-c1 - c2 - cr), inverse * c1, inverse * c2};
  for (int j = 0; j < 3; ++j) {
    const std::array<Eigen::RowVector3d, 3> dweight{-(dxi[j].row(0) + dxi[j].row(1)), dxi[j].row(0), dxi[j].row(1)};
    for (int i = 0; i < 3; ++i)
      out.hessian.block<3, 3>(3 * i, 3 * j) = -n * dweight[i] - out.weights[i] * dn[j];
  }
  return out;
}

std::vector<Eigen::Vector3d> sharp_feature_points(const geometry::TriangleMesh& needle, double spacing,
                                                  double edge_radius) {
  const auto& v = needle.vertices;
  const auto& t = needle.triangles;
  std::vector<Eigen::Vector3d> face_normal(t.size()), vertex_normal(v.size(), Eigen::Vector3d::Zero());
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  std::vector<std::vector<int>> vertex_faces(v.size());
  for (size_t f = 0; f < t.size(); ++f) {
    const Eigen::Vector3d m = (v[t[f][1]] - v[t[f][0]]).cross(v[t[f][2]] - v[t[f][0]]);
    face_normal[f] = m.norm() > 0 ? Eigen::Vector3d(m.normalized()) : Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int a = t[f][k], b = t[f][(k + 1) % 3];
      const Eigen::Vector3d e1 = (v[b] - v[a]).normalized(), e2 = (v[t[f][(k + 2) % 3]] - v[a]).normalized();
      vertex_normal[a] += std::acos(std::clamp(e1.dot(e2), -1.0, 1.0)) * face_normal[f];  // angle-weighted
      vertex_faces[a].push_back(static_cast<int>(f));
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  }
  for (auto& n : vertex_normal)
    if (n.norm() > 0) n.normalize();
  const double cos_sharp = std::cos(kSharpAngle);
  std::vector<char> sharp_vertex(v.size(), 0);
  std::vector<Eigen::Vector3d> points;
  for (const auto& [edge, faces] : edge_faces) {
    if (faces.size() != 2) continue;
    const Eigen::Vector3d &n0 = face_normal[faces[0]], &n1 = face_normal[faces[1]];
    int opposite = 0;  // the vertex of the second face off the edge: below the first face's plane when convex
    for (int c : t[faces[1]])
      if (c != edge.first && c != edge.second) opposite = c;
    if (n0.dot(n1) >= cos_sharp || (v[opposite] - v[edge.first]).dot(n0) >= 0) continue;
    sharp_vertex[edge.first] = sharp_vertex[edge.second] = 1;
    const Eigen::Vector3d out = (n0 + n1).normalized() * edge_radius;
    const int pieces = static_cast<int>(std::ceil((v[edge.second] - v[edge.first]).norm() / spacing));
    for (int s = 1; s < pieces; ++s)
      points.push_back(v[edge.first] + (v[edge.second] - v[edge.first]) * (double(s) / pieces) + out);
  }
  for (size_t a = 0; a < v.size(); ++a) {
    if (!sharp_vertex[a]) {  // a cone's apex: convex, its faces' normals spread by more than kSharpAngle
      bool spread = false, convex = true;
      for (int f : vertex_faces[a]) {
        for (int g : vertex_faces[a]) spread = spread || face_normal[f].dot(face_normal[g]) < cos_sharp;
        for (int c : t[f]) convex = convex && (c == static_cast<int>(a) || (v[c] - v[a]).dot(vertex_normal[a]) < 0);
      }
      sharp_vertex[a] = spread && convex;
    }
    if (sharp_vertex[a]) points.push_back(v[a] + edge_radius * vertex_normal[a]);
  }
  return points;
}

NeedleEdgeContact::NeedleEdgeContact(const TopSurface& top, const std::vector<double>& node_stiffness,
                                     std::vector<Eigen::Vector3d> points, const Eigen::Vector3d& direction)
    : top_(top), node_stiffness_(node_stiffness), points_(std::move(points)), direction_(direction.normalized()) {
  top_index_.assign(top.node_area.size(), -1);
  for (size_t k = 0; k < top.nodes.size(); ++k) top_index_[static_cast<size_t>(top.nodes[k])] = static_cast<int>(k);
  gap_now_.assign(points_.size(), std::numeric_limits<double>::infinity());
}

// The (point, face) pairs at (u, d): every face whose plane the point is near (within the face's size) and whose
// interior, widened by kMargin, holds its projection.
void NeedleEdgeContact::search(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d) {
  const auto position = [&](int a) -> Eigen::Vector3d { return nodes[a] + u.segment<3>(3 * a); };
  // The triangles near the needle's points: deformed box within a triangle's reach (its reference size) of theirs.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : points_) lo = lo.cwiseMin(p + d * direction_), hi = hi.cwiseMax(p + d * direction_);
  struct Candidate {
    int triangle;
    double reach;
    Eigen::Vector3d lo, hi;
  };
  std::vector<Candidate> near;
  for (size_t f = 0; f < top_.triangles.size(); ++f) {
    const auto& tri = top_.triangles[f];
    const double reach = std::min({top_.node_size[tri[0]], top_.node_size[tri[1]], top_.node_size[tri[2]]});
    Candidate c{static_cast<int>(f), reach, position(tri[0]), position(tri[0])};
    for (int k = 1; k < 3; ++k) c.lo = c.lo.cwiseMin(position(tri[k])), c.hi = c.hi.cwiseMax(position(tri[k]));
    c.lo.array() -= reach;
    c.hi.array() += reach;
    if ((c.hi.array() >= lo.array()).all() && (c.lo.array() <= hi.array()).all()) near.push_back(c);
  }
  pairs_.clear();
  size_t kept = 0;  // kept_pairs_ is sorted by point
  for (size_t i = 0; i < points_.size(); ++i) {
    const Eigen::Vector3d p = points_[i] + d * direction_;
    const auto first = static_cast<std::ptrdiff_t>(pairs_.size());
    // Where the tissue's surface folds into a valley round the tip, the point is held by each face of it at once.
    for (const Candidate& c : near) {
      if ((p.array() < c.lo.array()).any() || (p.array() > c.hi.array()).any()) continue;
      const auto& tri = top_.triangles[static_cast<size_t>(c.triangle)];
      const Projection pr = project(p, position(tri[0]), position(tri[1]), position(tri[2]));
      if (pr.over() && std::abs(pr.gap) <= c.reach) pairs_.emplace_back(i, c.triangle);
    }
    // The faces the point was over at the last converged state hold it through the step while it stays over them
    // (widened by kKeptMargin): at the step's first evaluation the needle has moved on and the surface not yet (the
    // tip of a sharp bevel started each step a whole element under the faces it had met, out of their reach, and
    // went through them).
    const auto found = static_cast<std::ptrdiff_t>(pairs_.size());
    for (; kept < kept_pairs_.size() && kept_pairs_[kept].first == i; ++kept) {
      const int face = kept_pairs_[kept].second;
      if (std::any_of(pairs_.begin() + first, pairs_.begin() + found,
                      [&](const auto& pair) { return pair.second == face; }))
        continue;
      const auto& tri = top_.triangles[static_cast<size_t>(face)];
      const Projection pr = project(p, position(tri[0]), position(tri[1]), position(tri[2]));
      if (pr.over(kKeptMargin)) pairs_.emplace_back(i, face);
    }
  }
}

double NeedleEdgeContact::evaluate(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d,
                                   bool want_force, bool want_tangent, Eigen::VectorXd& force,
                                   const std::vector<int>& free_index, const UpperPattern& pattern,
                                   std::vector<double>& values) {
  force_on_needle_.setZero();
  moment_on_needle_.setZero();
  force_now_.clear();
  std::fill(gap_now_.begin(), gap_now_.end(), std::numeric_limits<double>::infinity());
  if (points_.empty()) return 0;
  const auto position = [&](int a) -> Eigen::Vector3d { return nodes[a] + u.segment<3>(3 * a); };
  const size_t faces = top_.triangles.size();
  search(nodes, u, d);
  double energy = 0;
  for (const auto& [i, face] : pairs_) {
    const Eigen::Vector3d p = points_[i] + d * direction_;
    const auto& tri = top_.triangles[static_cast<size_t>(face)];
    const std::array<int, 3> corner{tri[0], tri[1], tri[2]};
    const PlaneGap g = triangle_plane_gap(p, position(corner[0]), position(corner[1]), position(corner[2]));
    const double k = (node_stiffness_[top_index_[corner[0]]] + node_stiffness_[top_index_[corner[1]]] +
                      node_stiffness_[top_index_[corner[2]]]) / 3;
    const size_t key = i * faces + static_cast<size_t>(face);
    const auto held = lambda_.find(key);
    const double pressure = (held == lambda_.end() ? 0.0 : held->second) - k * g.gap;
    gap_now_[i] = std::min(gap_now_[i], g.gap);
    if (pressure <= 0) continue;
    energy += pressure * pressure / (2 * k);
    force_now_[key] = pressure;
    force_on_needle_ += pressure * g.normal;
    moment_on_needle_ += points_[i].cross(pressure * g.normal);
    if (want_force)  // -dE/dx_i = P dg/dx_i
      for (int a = 0; a < 3; ++a) force.segment<3>(3 * corner[a]) += pressure * g.gradient.segment<3>(3 * a);
    if (want_tangent) {  // the exact tangent k grad g grad g^T - P hess g
      Eigen::Matrix<double, 9, 9> curvature = -pressure * 0.5 * (g.hessian + g.hessian.transpose());
      if (positive_curvature_) curvature = positive_part<9>(curvature);
      add_node_block<3>(corner, Eigen::Matrix<double, 9, 9>(k * g.gradient * g.gradient.transpose() + curvature),
                        free_index, pattern, values);
    }
  }
  return energy;
}

std::array<int, 3> NeedleEdgeContact::face_corners(size_t face) const {
  const auto& t = top_.triangles[face];
  std::array<int, 3> corners{top_index_[t[0]], top_index_[t[1]], top_index_[t[2]]};
  std::sort(corners.begin(), corners.end());
  return corners;
}

std::vector<NeedleEdgeContact::HeldPair> NeedleEdgeContact::held_pairs() const {
  std::vector<HeldPair> out;
  const size_t faces = top_.triangles.size();
  for (const auto& [key, multiplier] : lambda_) out.push_back({key / faces, face_corners(key % faces), multiplier});
  return out;
}

void NeedleEdgeContact::set_held_pairs(const std::vector<HeldPair>& pairs) {
  std::map<std::array<int, 3>, size_t> face_of;
  const size_t faces = top_.triangles.size();
  for (size_t f = 0; f < faces; ++f) face_of.emplace(face_corners(f), f);
  lambda_.clear();
  for (const HeldPair& pair : pairs) {
    const auto face = face_of.find(pair.top_nodes);
    if (face != face_of.end() && pair.point < points_.size())
      lambda_[pair.point * faces + face->second] = pair.multiplier;
  }
}

double NeedleEdgeContact::max_penetration() const {
  double pen = 0;
  for (double gap : gap_now_)
    if (std::isfinite(gap)) pen = std::max(pen, -gap);
  return pen;
}

void NeedleEdgeContact::hash_active(size_t& hash) const {
  // ~key: apart from the first pass's indices
  for (const auto& [key, pressure] : force_now_) hash = (hash ^ (~key)) * 1099511628211ull;
}

}  // namespace needlekit::fem::detail
