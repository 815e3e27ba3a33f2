// Nonlinear quasi-static indentation of a tetrahedral tissue block by rigid needles (dissertation §3.4).
//
// Total-Lagrangian tetrahedra (linear, or quadratic T10 built from the linear mesh by adding mid-edge nodes) with
// the Green-Lagrange strain (Eq 3.3 as corrected in the notes), the dissertation's linear stress-strain law
// S = D E (Eqs 3.4/3.5, i.e. St Venant-Kirchhoff) or a compressible neo-Hookean law. The prescribed needle
// displacement is applied in load steps; the first iterate of the first step is the linear elastic solution (§3.4:
// "we apply the solution obtained from the linear finite element as our initial guessed answer"), later steps start
// from the last converged state plus the last increment (or, optionally, the linearised solution about it). Each
// step is solved by Newton's method with a backtracking line search on the total potential energy (the problem is
// conservative; this replaces Matlab's trust-region dogleg of §3.4 and plays the same role); a failed step is cut
// back automatically. Linear systems: CHOLMOD supernodal Cholesky (symbolic analysis once per solver), used
// directly or as the preconditioner of conjugate gradients while a fresh factorization would cost more (inexact
// Newton). Element assembly is threaded (TBB).
//
// The needle is a rigid indenter in one of two models:
//  - ContactModel::TipNodes, the dissertation's rule (§3.4, Eq 3.9-3.12): the top-surface nodes under the needle's
//    flat tip face follow the tip along the indentation direction and are free across it (frictionless); the
//    reaction force is the sum of their internal forces (Eq 3.11). Only a flat tip face defines such nodes; for a
//    sharp tip the single top node nearest to the apex is used.
//  - ContactModel::Surface: frictionless unilateral contact of the tissue's top-surface nodes against the needle's
//    actual (closed) surface mesh, node-to-surface, enforced by a penalty with augmented-Lagrangian updates (the
//    multipliers are updated between Newton solves until the penetration is below a tolerance). Cones and bevels
//    indent with their real shape.
// Several needles may indent at once; they all move by the same displacement along their own directions.
//
// Frame (tet_mesh.hpp): tissue top surface z = 0, tissue z <= 0, needles above moving in -z. SI units throughout.
#pragma once
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/fem/solver_options.hpp"
#include "needlekit/mesh/tet_mesh.hpp"
#include "needlekit/mesh/coarse_level.hpp"

namespace needlekit::fem {

// How a load step ended. The numerical failures say which part of the solver gave way.
enum class StepStatus {
  Converged,            // the target displacement was reached
  InvertedElement,      // every cut-back still inverted an element (J <= 0 at a quadrature point)
  IterationLimit,       // Newton did not reach the tolerances within max_iterations (or the residual was not finite)
  LinearSolverFailure,  // the tangent system could not be solved (factorization or CG failed, also shifted)
  ContactCycling,       // Newton did not converge while the set of contact nodes kept changing between iterations
  InvalidTarget,        // the target displacement is not finite
};
inline constexpr EnumTable<StepStatus, 6> kStepStatusNames{{
    {StepStatus::Converged, "converged", "the target displacement was reached"},
    {StepStatus::InvertedElement, "inverted-element", "every cut-back still inverted an element (J <= 0)"},
    {StepStatus::IterationLimit, "newton-iteration-limit", "Newton did not reach the tolerances within max_iterations"},
    {StepStatus::LinearSolverFailure, "linear-solver-failure", "the tangent system could not be solved"},
    {StepStatus::ContactCycling, "contact-cycling",
     "Newton did not converge while the set of contact nodes kept changing"},
    {StepStatus::InvalidTarget, "invalid-target", "the target displacement is not finite"},
}};
std::string_view to_string(StepStatus status);

// How advance_to with a start (a warm start) came to balance.
enum class StartBalance { NoStart, Newton, Eased, Reloaded };
inline constexpr EnumTable<StartBalance, 4> kStartBalanceNames{{
    {StartBalance::NoStart, "no-start", "the step was not given a start"},
    {StartBalance::Newton, "newton", "Newton converged from the start"},
    {StartBalance::Eased, "eased",
     "the start's out-of-balance force was applied as a load and taken off in stages at the fixed needle"},
    {StartBalance::Reloaded, "reloaded", "the start was dropped and the step loaded from the last converged state"},
}};
std::string_view to_string(StartBalance balance);

struct StepResult {
  bool converged = false;                // status == StepStatus::Converged
  StepStatus status = StepStatus::Converged;
  std::string reason;                    // empty when converged; else what failed and at which displacement
  int newton_iterations = 0;             // total over substeps and augmentations
  int cutbacks = 0;
  int substeps = 0;                      // converged substeps taken
  double indenter_displacement = 0;      // m, displacement actually reached (== target when converged)
  StartBalance start_balance = StartBalance::NoStart;  // advance_to with a start: how it came to balance
  std::vector<double> indenter_force;    // N, per needle: reaction on the needle along -direction (>0 pushing)
  std::vector<double> max_contact_pressure;   // Pa, per needle: largest nodal contact pressure
  std::vector<double> mean_contact_pressure;  // Pa, per needle: force / contact area
  std::vector<double> contact_area;           // m^2, per needle: tributary area of the nodes in contact
  std::vector<int> contact_nodes;             // per needle: nodes in contact
  double max_penetration = 0;            // m, Surface contact: largest penetration after the last augmentation
  // The smallest volume ratio J = det F at any quadrature point: how far the most compressed tetrahedron is crushed
  // (the nodal-averaged volume lets single elements compress while their patch keeps its volume).
  double min_volume_ratio = 1;
  // m, Surface contact: how far the needles' tips lie inside the tissue past its top surface (the deepest tip point
  // inside a tetrahedron, by its distance to the deformed top surface; 0: none). Node-to-surface contact lets a tip
  // narrower than a few elements cut between the tissue's nodes (docs/fem_solver.md, "Tunnelling").
  double tip_embedded_depth = 0;
  double strain_energy = 0;              // J, stored in the tissue
  double external_work = 0;              // J, sum over needles of the trapezoidal integral of force over displacement
                                         // since the solver was built
  std::vector<IterationRecord> iterations;  // all Newton iterations of this call
  int factorizations = 0;                // numeric factorizations in this call
  double assembly_seconds = 0;           // totals of this call
  double solve_seconds = 0;
  double total_seconds = 0;
  std::vector<Eigen::Vector3d> contact_force;  // N, per needle: the tissue's resultant force on the needle (Surface:
                                               // normal and friction forces of both passes; TipNodes: -indenter_force
                                               // along the direction)
  // N m, per needle: the moment of the same forces about the point of the needle that was at the tissue frame's
  // origin at zero displacement (the forces' points taken relative to the needle, so that the moment about a point p
  // of the needle as placed is contact_moment - p x contact_force)
  std::vector<Eigen::Vector3d> contact_moment;
};

// Per-element outputs (one value per tetrahedron, averaged over its quadrature points) for VTU.
struct ElementFields {
  std::vector<Eigen::Matrix3d> cauchy_stress;   // Pa
  std::vector<double> von_mises_stress;         // Pa
  std::vector<double> strain_energy_density;    // J/m^3 of reference volume
  std::vector<double> volume_ratio;             // J = det F
};

class QuasiStaticSolver {
public:
  // Throws InvalidInput for an invalid mesh (empty, inverted or degenerate tetrahedra, a layer index out of range,
  // E <= 0, nu outside (-1, 0.5)), an indenter whose surface is empty or starts inside the tissue (below z = 0 by
  // more than the tolerance), or invalid options (naming the field). `coarse`: a coarse level of `mesh` for the
  // two-grid solver (mesh::refine_uniformly, mesh::interpolating_coarse_level); only read here.
  QuasiStaticSolver(const mesh::TetMesh& mesh, std::vector<Indenter> indenters, SolverOptions options = {},
                    const mesh::CoarseLevel* coarse = nullptr);
  ~QuasiStaticSolver();
  QuasiStaticSolver(QuasiStaticSolver&&) noexcept;
  QuasiStaticSolver& operator=(QuasiStaticSolver&&) noexcept;

  // One load step from the last converged state to the needle displacement `indenter_displacement` (m, may be
  // smaller than the current one), with automatic cut-back. Never throws for numerical failure: the result says
  // where and why it stopped, and the solver keeps the last converged state.
  StepResult advance_to(double indenter_displacement);
  // The same step with Newton started from `start` (m, one vector per node of nodes()) instead of the predictor: a
  // warm start from the same step of a run on the same mesh with slightly different parameters (the finite
  // differences of a calibration, or a rezoned mesh's transferred state). The prescribed dofs are set as usual. When
  // Newton from the start does not converge, the start's residual is applied as a load and taken off in stages
  // (StepResult::start_balance); when that fails too, with `reload` the start is dropped and the step runs as
  // advance_to would, and without it the step fails (a rezoning: loaded from zero, the new mesh would lose the
  // contact history, and a sharp tip went through the tissue). `start` of another size is an std::invalid_argument.
  StepResult advance_to(double indenter_displacement, const std::vector<Eigen::Vector3d>& start, bool reload = true);

  double indenter_displacement() const;                    // m, last converged
  const std::vector<Eigen::Vector3d>& nodes() const;       // reference positions: the mesh's nodes, then (T10)
                                                           // one mid-edge node per edge
  const std::vector<Eigen::Vector3d>& displacement() const;  // m, per node of nodes()
  // Element connectivity into nodes(): 4 or 10 indices per tet, VTK order (corners, then the mid-points of edges
  // 01, 12, 20, 03, 13, 23).
  const std::vector<std::vector<int>>& elements() const;
  const std::vector<int>& contact_flag() const;            // per node: 0, or 1 + needle index in contact
  const std::vector<double>& contact_pressure() const;     // Pa, per node (0 where not in contact)
  // m^2, per node: its tributary area of the top surface (the area contact_pressure acts on; 0 off the top surface)
  const std::vector<double>& top_node_area() const;
  ElementFields element_fields() const;
  const SolverOptions& options() const;
  int dof_count() const;        // 3 * nodes
  int free_dof_count() const;   // unknowns of the linear systems
  LinearSolver linear_solver() const;  // the one in use (never Automatic)
  // Linear tetrahedra whose volume is averaged at the nodes (VolumetricFormulation), of all elements.
  int nodal_average_elements() const;

  // The total potential energy (strain + contact), its gradient over the free dofs (the residual) and its dense
  // tangent at the displacement `u` (one vector per node of nodes(); prescribed dofs as given) with the needles at
  // `indenter_displacement`: for verification on small meshes (tangent vs finite differences). Uses the solver's
  // work space: call advance_to (which re-evaluates its converged state) before reading outputs again.
  struct Linearization {
    bool valid = true;            // false: an element or a nodal volume inverted
    double energy = 0;            // J
    Eigen::VectorXd gradient;     // N, per free dof, in ascending dof (3 * node + component) order
    Eigen::MatrixXd tangent;      // N/m, free x free (the gradient's order), symmetric: the exact one (never the
                                  // contact curvature's positive part that a Newton solve may fall back to)
  };
  Linearization linearization(const std::vector<Eigen::Vector3d>& u, double indenter_displacement);

  // Surface contact's history at the last converged state: the augmented-Lagrangian multipliers and the friction
  // states of the top-surface nodes (opaque). For a solver on a rezoned mesh of the same tissue, whose top-surface
  // nodes are these, in the same order (mesh/rezoned_mesh.hpp): set_contact_history gives them the history, so that
  // the rezoning neither loses the multipliers nor restarts stick and slip. set_contact_history returns false (and
  // changes nothing) for a history of another top surface or needle count, or without surface contact.
  struct ContactHistory;
  std::shared_ptr<const ContactHistory> contact_history() const;
  bool set_contact_history(const ContactHistory& history);

  // Of the Cholesky factor in use (TwoGrid: the coarse level's): its entries (about 8 bytes each) and the
  // floating-point operations of one numeric factorization.
  double factor_nonzeros() const;
  double factor_flops() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace needlekit::fem
