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
// g = (p - x0) . n, n = (x1 - x0) x (x2 - x0) / |...| (Wriggers 2006 §4.1, node-to-segment), taken on the triangle
// whose plane is nearest among those the point projects into. That face is searched at the first evaluation after
// an augmentation, a converged step or a restore, and kept through the Newton solve (FEBio's segment updates): the
// gap jumps where neighbouring faces meet at an angle, and a search at every iteration made Newton cycle. Energy (lambda - k g)^2 / (2 k) while positive; its
// forces and its exact tangent k grad g grad g^T - P hess g (the second derivative of g in the triangle's nodes,
// triangle_plane_gap) make the contact tangent consistent.
#pragma once
#include <Eigen/Core>
#include <array>
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
  void augment() { lambda_ = force_now_, search_ = true; }
  const std::vector<double>& multipliers() const { return lambda_; }
  void set_multipliers(const std::vector<double>& lambda) { lambda_ = lambda, search_ = true; }
  // A load step converged: the next evaluation searches the faces again.
  void search_again() { search_ = true; }
  // The tissue's force on the needle at the last evaluation (N, world axes) and the active points' indices hashed
  // into `hash` (FNV-1a).
  const Eigen::Vector3d& force_on_needle() const { return force_on_needle_; }
  // Its moment about the origin of the needle's frame at zero displacement (the points as placed), N m.
  const Eigen::Vector3d& moment_on_needle() const { return moment_on_needle_; }
  void hash_active(size_t& hash) const;
  size_t point_count() const { return points_.size(); }

private:
  const TopSurface& top_;
  std::vector<int> top_index_;         // per function-space node: index into top.nodes, or -1
  const std::vector<double>& node_stiffness_;
  std::vector<Eigen::Vector3d> points_;
  Eigen::Vector3d direction_;
  std::vector<double> lambda_, force_now_, gap_now_;
  std::vector<int> face_;  // per point: the tissue face it is held against (index into top.triangles), -1: none
  bool search_ = true;
  Eigen::Vector3d force_on_needle_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_on_needle_ = Eigen::Vector3d::Zero();
};

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
