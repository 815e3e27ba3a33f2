// Internal: frictionless unilateral node-to-surface contact of the tissue's top-surface nodes against rigid needle
// meshes (ContactModel::Surface), enforced by a penalty with augmented-Lagrangian multipliers (the multipliers are
// updated between Newton solves until the penetration is below a tolerance; Simo & Laursen 1992). The penalty
// stiffness of a node is penalty_factor * E / h * (its tributary area).
#pragma once
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "boundary_conditions.hpp"
#include "needlekit/fem/solver_options.hpp"
#include "rigid_surface_distance.hpp"
#include "sparse_pattern.hpp"

namespace needlekit::fem::detail {

class SurfaceContact {
public:
  SurfaceContact(const TopSurface& top, const FunctionSpace& space, const std::vector<Indenter>& needles,
                 double penalty_factor);

  // Contact energy of the state (u, needle displacement d); with `want_force` the contact forces into `force`
  // (per dof, zeroed first), with `want_tangent` the penalty tangent k n n^T added into `values` (pattern over the
  // free dofs). Records each node's gap, force and normal.
  double evaluate(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d, bool want_force,
                  bool want_tangent, Eigen::VectorXd& force, const std::vector<int>& free_index,
                  const UpperPattern& pattern, std::vector<double>& values);

  // Largest penetration at the last evaluation, m.
  double max_penetration() const;
  // Augmented-Lagrangian update: multipliers = the contact forces of the last evaluation.
  void augment();
  // Which top nodes are ahead of each needle in the converged state (u, d): their nearest point on the needle's
  // surface has an outward normal along the direction of motion (under a leading face or its rim), or they are out
  // of reach. Nodes beside the needle (nearest a side wall) are not.
  void update_ahead(const std::vector<Eigen::Vector3d>& nodes, const Eigen::VectorXd& u, double d);
  // The multipliers of every needle, to restore after a failed step.
  std::vector<std::vector<double>> multipliers() const;
  void set_multipliers(const std::vector<std::vector<double>>& multipliers);
  // Number of (node, needle) pairs in contact at the last evaluation and a fingerprint of that set.
  size_t active_set_fingerprint() const;

  // Per top node (index into top.nodes) and needle: the contact force at the last evaluation (N, >= 0) and its
  // component along the needle's direction.
  double node_force(size_t needle, size_t top_index) const { return needles_[needle].force_now[top_index]; }
  double axial_force(size_t needle, size_t top_index) const {
    return needles_[needle].force_now[top_index] * needles_[needle].normal_now[top_index].dot(needles_[needle].direction);
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
    std::vector<char> ahead;        // per top node, under the needle's leading faces at the last converged state
                                    // (see RigidSurfaceDistance::signed_distance)
  };
  const std::vector<int>& top_nodes_;
  std::vector<double> stiffness_;  // per top node (index into top_nodes_), N/m
  double h_min_ = 0;
  std::vector<NeedleContact> needles_;
};

}  // namespace needlekit::fem::detail
