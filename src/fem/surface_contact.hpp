// Internal: unilateral node-to-surface contact of the tissue's top-surface nodes against rigid needle meshes
// (ContactModel::Surface), enforced by a penalty with augmented-Lagrangian multipliers (the multipliers are updated
// between Newton solves until the penetration is below a tolerance; Simo & Laursen 1992), with Coulomb friction
// (coulomb_friction.hpp) when SolverOptions::friction > 0, and the second pass of the needle's sharp features against
// the tissue's faces (needle_edge_contact.hpp) when SolverOptions::two_pass. The penalty stiffness of a node is penalty_factor * E / h * (its
// tributary area); the tangential one the same.
#pragma once
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "boundary_conditions.hpp"
#include "coulomb_friction.hpp"
#include "needle_edge_contact.hpp"
#include "needlekit/fem/solver_options.hpp"
#include "rigid_surface_distance.hpp"
#include "sparse_pattern.hpp"

namespace needlekit::fem::detail {

class SurfaceContact {
public:
  // The options' penalty_factor, friction and two_pass apply.
  SurfaceContact(const TopSurface& top, const FunctionSpace& space, const std::vector<Indenter>& needles,
                 const SolverOptions& options);

  // Contact energy of the state (u, needle displacement d); with `want_force` the contact forces into `force`
  // (per dof, zeroed first), with `want_tangent` the penalty tangent k n n^T added into `values` (pattern over the
  // free dofs). Records each node's gap, force and normal.
  double evaluate(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d, bool want_force,
                  bool want_tangent, Eigen::VectorXd& force, const std::vector<int>& free_index,
                  const UpperPattern& pattern, std::vector<double>& values);

  // Both passes' tangents with the positive part of their curvature only (the first pass's -P hess g of a node on a
  // needle's rounded edge, NeedleEdgeContact::set_positive_curvature for the second); false when neither has a
  // curvature to modify (sharp needles without a second pass).
  bool set_positive_curvature(bool on) {
    bool any = false;
    positive_curvature_ = on;
    for (auto& nd : needles_)
      nd.edges.set_positive_curvature(on), any = any || nd.edges.point_count() > 0 || nd.distance->offset() > 0;
    return any;
  }
  // Largest penetration at the last evaluation, m.
  double max_penetration() const;
  // Augmented-Lagrangian update: multipliers = the contact forces of the last evaluation; friction bounds = the
  // coefficient times them, in the tangent planes of the last evaluation.
  void augment();
  // Whether the friction bounds are within kFrictionBoundTolerance of the coefficient times the normal forces of the
  // last evaluation (always without friction).
  bool friction_settled() const;
  // A load step converged at (u, d): the friction's reference positions and forces become the current ones.
  void commit_friction(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d);
  // Which top nodes are ahead of each needle in the converged state (u, d): their nearest point on the needle's
  // surface has an outward normal along the direction of motion (under a leading face or its rim), or they are out
  // of reach. Nodes beside the needle (nearest a side wall) are not.
  void update_ahead(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d);
  // The multipliers and friction states of every needle, to restore after a failed step.
  struct Multipliers {
    std::vector<std::vector<double>> nodes;
    std::vector<NeedleEdgeContact::PairForces> edges;
    std::vector<std::vector<FrictionState>> friction;
  };
  Multipliers multipliers() const;
  void set_multipliers(const Multipliers& multipliers);
  // Back to the needles at rest: no multipliers, no friction history, no faces kept by the second pass (a warm start
  // from another mesh's state failed and the load path starts again from zero).
  void forget_history();
  // The second pass's multipliers per needle with faces named by their corners (NeedleEdgeContact::held_pairs).
  std::vector<std::vector<NeedleEdgeContact::HeldPair>> held_pairs() const {
    std::vector<std::vector<NeedleEdgeContact::HeldPair>> out;
    for (const auto& nd : needles_) out.push_back(nd.edges.held_pairs());
    return out;
  }
  void set_held_pairs(const std::vector<std::vector<NeedleEdgeContact::HeldPair>>& pairs) {
    for (size_t k = 0; k < needles_.size() && k < pairs.size(); ++k) needles_[k].edges.set_held_pairs(pairs[k]);
  }
  // Number of (node, needle) pairs in contact at the last evaluation and a fingerprint of that set.
  size_t active_set_fingerprint() const;

  // Per top node (index into top.nodes) and needle: the contact force at the last evaluation (N, >= 0) and its
  // component along the needle's direction.
  double node_force(size_t needle, size_t top_index) const { return needles_[needle].force_now[top_index]; }
  double axial_force(size_t needle, size_t top_index) const {
    const NeedleContact& nd = needles_[needle];
    return (nd.force_now[top_index] * nd.normal_now[top_index] - nd.traction_now[top_index]).dot(nd.direction);
  }
  // The tissue's resultant force on a needle at the last evaluation, N: both passes, with friction.
  Eigen::Vector3d force_on_needle(size_t needle) const;
  // Its moment about the origin of the needle's frame at zero displacement (the needle as placed: the contact points
  // taken relative to the needle), N m.
  Eigen::Vector3d moment_on_needle(size_t needle) const;
  // The second pass's share of it along -direction (the needle's points against the tissue's faces), N.
  double edge_axial_force(size_t needle) const {
    return -needles_[needle].edges.force_on_needle().dot(needles_[needle].direction);
  }
  // The smallest element size at the top, m.
  double smallest_size() const { return h_min_; }

private:
  struct NeedleContact {
    Eigen::Vector3d direction;
    std::unique_ptr<RigidSurfaceDistance> distance;
    std::vector<double> lambda;     // augmented-Lagrangian force per top node, N
    std::vector<double> gap_now;    // signed gap per top node at the last evaluation, m
    std::vector<double> force_now;  // contact force per top node, N
    std::vector<Eigen::Vector3d> normal_now;
    std::vector<Eigen::Vector3d> position_now;   // per top node: relative() at the last evaluation, m
    std::vector<char> ahead;        // per top node, under the needle's leading faces at the last converged state
                                    // (see RigidSurfaceDistance::signed_distance)
    std::vector<FrictionState> friction;         // per top node
    std::vector<Eigen::Vector3d> traction_now;   // per top node: friction force on the needle, N
    NeedleEdgeContact edges;                     // the second pass
  };
  // The node's position in the needle's frame.
  Eigen::Vector3d relative(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d,
                           const NeedleContact& nd, size_t t) const {
    const int a = top_nodes_[t];
    return nodes[a] + u.segment<3>(3 * a) - d * nd.direction;
  }
  const std::vector<int>& top_nodes_;
  std::vector<double> stiffness_;  // per top node (index into top_nodes_), N/m
  double h_min_ = 0;
  double friction_ = 0;            // Coulomb coefficient, >= 0
  bool positive_curvature_ = false;  // set_positive_curvature
  std::vector<NeedleContact> needles_;
  std::vector<FrictionState> at_rest_;  // per top node: the friction state with the needle at d = 0
};

}  // namespace needlekit::fem::detail
