// Internal: the second pass of surface contact (ContactModel::Surface): the rigid needle's sharp features against
// the tissue's deformed top-surface triangles. The first pass (surface_contact.hpp) keeps the tissue's nodes out of
// the needle; between nodes, a needle's rim or apex can still cut into the tissue's faces, and nodes under a thin tip
// slide round the rim (docs/indentation.md). Here points on the needle's sharp edges (dihedral angle above
// kSharpAngle, convex) and at its sharp vertices, no farther apart than half the smallest top element, are each kept
// above the tissue surface: node-to-segment contact with the needle's points as the slave side and the tissue's
// faces as the master (the "two-pass" of Hallquist, Goudreau & Benson, CMAME 51, 1985; FEBio's two_pass), enforced
// by the same penalty and augmented-Lagrangian multipliers as the first pass (Simo & Laursen 1992), frictionless.
//
// The gap of a point p against a triangle (x0, x1, x2) is its signed distance to the triangle's plane,
// g = (p - x0) . n, n = (x1 - x0) x (x2 - x0) / |...| (Wriggers 2006 §4.1, node-to-segment). A point is held by
// every face near it whose interior, widened by kMargin, holds its projection, each (point, face) pair with its own
// multiplier: where the tissue's surface folds into a valley round the needle's tip, the tip is held by each face of
// the valley at once, as a solid that is locally the union of the faces' half-spaces. (One face per point, frozen
// through each Newton solve, let the §6.2 sharp bevel's apex slide off its face and through its neighbours: the tip
// lay 80-100 % of its depth inside the tissue, docs/fem_solver.md. The closest point over the whole surface gives a
// continuous gap, but on a ridge or in a valley its direction turns with the point's lateral motion over its
// nanometre distance, and Newton stalled.) The faces are searched at every evaluation, and those a point was over
// at the last converged state hold it through the next step while it stays over them widened by kKeptMargin: a tip
// that sits in a valley's crease lies just outside each of its faces, and a load step's predictor can leave it a few
// micrometres under the crease. Energy (lambda - k g)^2 / (2 k)
// per pair while positive; its forces and its exact tangent k grad g grad g^T - P hess g (the second derivative of g
// in the triangle's nodes, triangle_plane_gap) make the contact tangent consistent.
#pragma once
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <array>
#include <map>
#include <vector>

#include "boundary_conditions.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "sparse_pattern.hpp"

namespace needlekit::fem::detail {

// The signed distance of p to the plane of the triangle (x0, x1, x2) (positive on the side of its normal
// (x1 - x0) x (x2 - x0)), the barycentric coordinates of p's projection, the gradient (per node: -N_i n) and the
// Hessian in the nine node coordinates.
struct PlaneGap {
  double gap = 0;                                       // m
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();     // unit
  std::array<double, 3> weights{};                      // N_0, N_1, N_2 of the projection
  Eigen::Matrix<double, 9, 1> gradient;                 // dg / d(x0, x1, x2)
  Eigen::Matrix<double, 9, 9> hessian;                  // d^2 g / d(x0, x1, x2)^2, 1/m
};
PlaneGap triangle_plane_gap(const Eigen::Vector3d& p, const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                            const Eigen::Vector3d& x2);

// How far outside a face (in its barycentric coordinates) a point still counts as over it.
inline constexpr double kMargin = 0.05;
// The same for a face that held the point at the last converged state, through the next step. With kMargin for
// these too, the §6.2 sharp bevel's tip (40 um tip mesh, 25 um steps) sat in its valley's crease at 50 um, just
// outside both faces (barycentric -0.01 to -0.04), and was out of every face at the next step's start: it ran 20 um
// inside the tissue at 75 um. With half a face it stays held (0 um inside to 100 um, twenty-fourth session).
inline constexpr double kKeptMargin = 0.5;

// The points standing for a needle's sharp features, in its frame at zero displacement (m): along each convex edge
// whose faces meet at more than kSharpAngle (every `spacing` at most, ends included) and at each convex vertex whose
// faces' normals spread by more than kSharpAngle. `edge_radius`: each point moves out along its feature's
// pseudo-normal by it (the rounded needle of Indenter::edge_radius).
inline constexpr double kSharpAngle = 30.0 * 3.14159265358979323846 / 180;  // rad
std::vector<Eigen::Vector3d> sharp_feature_points(const geometry::TriangleMesh& needle, double spacing,
                                                  double edge_radius);

class NeedleEdgeContact {
public:
  // `node_stiffness`: the first pass's penalty stiffness per top node (index into top.nodes), N/m; a point's
  // stiffness is the mean of its triangle's nodes'.
  NeedleEdgeContact(const TopSurface& top, const std::vector<double>& node_stiffness,
                    std::vector<Eigen::Vector3d> points, const Eigen::Vector3d& direction);

  // Contact energy at (u, needle displacement d); forces added into `force` (not zeroed), the tangent into `values`.
  double evaluate(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d, bool want_force,
                  bool want_tangent, Eigen::VectorXd& force, const std::vector<int>& free_index,
                  const UpperPattern& pattern, std::vector<double>& values);
  double max_penetration() const;  // m, at the last evaluation
  // The multipliers per (point, face) pair, keyed point * (number of top faces) + face.
  using PairForces = std::map<size_t, double>;
  void augment() { lambda_ = force_now_; }
  // With `on`, the tangent keeps only the positive part of -P hess g (a face pressed at a point may tilt away: the
  // exact tangent can be indefinite): the Hessian modification of Nocedal & Wright (2006) §3.4, for a Newton
  // iteration whose exact tangent could not be factorized.
  void set_positive_curvature(bool on) { positive_curvature_ = on; }
  const PairForces& multipliers() const { return lambda_; }
  void set_multipliers(const PairForces& lambda) { lambda_ = lambda; }
  // A load step converged at (u, d): the pairs found there are kept through the next step (search()).
  void keep_pairs(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d) {
    kept_pairs_.clear();
    search(nodes, u, d);
    kept_pairs_ = pairs_;
  }
  void drop_kept_pairs() { kept_pairs_.clear(); }
  // The multipliers with each face named by its corners (indices into top.nodes, ascending) instead of its number:
  // they carry over to another mesh whose top surface has the same nodes in the same order (a rezoning keeps them).
  struct HeldPair {
    size_t point;
    std::array<int, 3> top_nodes;
    double multiplier;  // N
  };
  std::vector<HeldPair> held_pairs() const;
  // Pairs whose face is not one of this mesh's top faces are dropped.
  void set_held_pairs(const std::vector<HeldPair>& pairs);
  // The tissue's force on the needle at the last evaluation (N, world axes) and the active pairs' keys hashed
  // into `hash` (FNV-1a).
  const Eigen::Vector3d& force_on_needle() const { return force_on_needle_; }
  // Its moment about the origin of the needle's frame at zero displacement (the points as placed), N m.
  const Eigen::Vector3d& moment_on_needle() const { return moment_on_needle_; }
  void hash_active(size_t& hash) const;
  size_t point_count() const { return points_.size(); }
  // The (point, face) pairs in contact at the last evaluation.
  size_t active_pairs() const { return force_now_.size(); }

private:
  void search(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d);
  std::array<int, 3> face_corners(size_t face) const;  // indices into top.nodes, ascending

  const TopSurface& top_;
  std::vector<int> top_index_;         // per function-space node: index into top.nodes, or -1
  const std::vector<double>& node_stiffness_;
  std::vector<Eigen::Vector3d> points_;
  Eigen::Vector3d direction_;
  PairForces lambda_, force_now_;
  bool positive_curvature_ = false;
  std::vector<std::pair<size_t, int>> pairs_;  // (point, face) pairs found by the last search, by point
  std::vector<std::pair<size_t, int>> kept_pairs_;  // those at the last converged state
  std::vector<double> gap_now_;  // per point: its smallest plane gap at the last evaluation, m
  Eigen::Vector3d force_on_needle_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_on_needle_ = Eigen::Vector3d::Zero();
};

// The positive part of a symmetric matrix (its negative eigenvalues set to zero): the Hessian modification of
// Nocedal & Wright (2006) §3.4 that both passes' tangents fall back to when the exact one cannot be solved.
template <int N>
Eigen::Matrix<double, N, N> positive_part(const Eigen::Matrix<double, N, N>& m) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(m);
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
}

// Adds the symmetric block `k` (3 N x 3 N, over the three dofs of each node in `nodes`) into the upper pattern over
// the free dofs.
template <int N>
void add_node_block(const std::array<int, N>& nodes, const Eigen::Matrix<double, 3 * N, 3 * N>& k,
                    const std::vector<int>& free_index, const UpperPattern& pattern, std::vector<double>& values) {
  for (int a = 0; a < N; ++a)
    for (int i = 0; i < 3; ++i) {
      const int r = free_index[3 * nodes[a] + i];
      if (r < 0) continue;
      for (int b = 0; b < N; ++b)
        for (int j = 0; j < 3; ++j) {
          const int c = free_index[3 * nodes[b] + j];
          if (c < 0 || r > c) continue;
          values[static_cast<size_t>(entry_position(pattern, r, c))] += k(3 * a + i, 3 * b + j);
        }
    }
}

}  // namespace needlekit::fem::detail
