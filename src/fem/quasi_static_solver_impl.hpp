// Internal: the state of QuasiStaticSolver, shared by quasi_static_solver.cpp (construction, assembly, outputs) and
// newton_step.cpp (load steps: predictor, Newton with line search, augmentations, cut-back).
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "boundary_conditions.hpp"
#include "function_space.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needle_embedding.hpp"
#include "nodal_volume.hpp"
#include "linear_solve.hpp"
#include "surface_contact.hpp"
#include "tangent_matrix.hpp"

namespace needlekit::fem {

struct QuasiStaticSolver::Impl {
  using Clock = std::chrono::steady_clock;
  static double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  }

  struct Needle {
    Indenter indenter;
    Eigen::Vector3d direction;  // unit
    double gap = 0;             // m, TipNodes: distance the needle travels before its tip touches the top surface
    std::vector<int> tip_nodes; // TipNodes
  };
  static Needle placed_needle(Indenter indenter, const std::string& name, const SolverOptions& options,
                              const detail::TopSurface& top, const detail::FunctionSpace& space, double tolerance);

  // Why a substep failed.
  struct Failure {
    StepStatus status = StepStatus::IterationLimit;
    std::string why;
    bool start_inverted = false;  // the (sub)step's start, before any Newton update, inverted an element
  };

  SolverOptions opt;
  detail::FunctionSpace space;
  detail::TopSurface top;
  detail::DofMap dofs;
  std::vector<Needle> needles;
  std::unique_ptr<detail::SurfaceContact> contact;  // Surface
  std::unique_ptr<detail::NeedleEmbedding> embedding;  // Surface: StepResult::tip_embedded_depth
  std::unique_ptr<detail::NodalVolumeAverage> nodal;  // linear tetrahedra with the nodal-averaged volume
  tbb::task_arena arena;
  std::unique_ptr<detail::TangentMatrix> tangent;     // the assembled K
  std::unique_ptr<detail::LinearSolve> linear_solve;  // K du = rhs, on `tangent`
  LinearSolver solver = LinearSolver::CholeskyCg;     // resolved (never Automatic)
  int ndof = 0;

  Eigen::VectorXd u, fint, fcontact;  // per dof: displacement, internal force, contact force
  std::vector<Eigen::Vector3d> u_nodes;
  double d = 0;                    // m, needle displacement of the converged state
  double external_work = 0;        // J
  std::vector<double> last_force;  // N, per needle at the converged state
  std::vector<int> contact_flag;
  std::vector<double> contact_pressure;
  Eigen::VectorXd last_increment;  // u change of the last converged substep (for the secant predictor)
  double last_step = 0;            // m, its needle displacement change
  Eigen::VectorXd earlier_increment;  // the substep's before it (the quadratic predictor), empty if none
  double earlier_step = 0;            // m
  int augmentation = 0;                // surface contact: the (sub)step's augmented-Lagrangian updates so far
  double converged_strain_energy = 0;  // J, of the state at which newton() last returned converged
  // Easing a warm start into balance (ease_into_balance): the start's residual r0 on the free dofs, and the share s
  // of it still applied as a load, so that the solver solves R(u) = s r0 (energy: Pi(u) - s r0 . u). Empty: none.
  Eigen::VectorXd start_residual;
  double start_share = 0;

  // ---- assembly (quasi_static_solver.cpp) ----
  struct Eval {
    double strain_energy = 0;
    double contact_energy = 0;
    double load_energy = 0;  // J, -s r0 . u while a warm start is eased into balance
    bool valid = true;
    int inverted_element = -1;  // when not valid: the lowest-numbered element found inverted (-1: none named)
    double potential() const { return strain_energy + contact_energy + load_energy; }
  };
  template <int N>
  Eval element_pass(const Eigen::VectorXd& uu, bool want_force, bool want_tangent, const Eigen::VectorXd* dup,
                    Eigen::VectorXd* kdup);
  // Energy; with want_force the internal and contact forces (fint, fcontact); with want_tangent the tangent into
  // the system's values; with dup the product K_fp dup of the prescribed dofs into kdup (the linear predictor).
  Eval evaluate(const Eigen::VectorXd& uu, double disp, bool want_force, bool want_tangent,
                const Eigen::VectorXd* dup = nullptr, Eigen::VectorXd* kdup = nullptr);
  // The PETSc backend on several processes, after element_pass over this process's elements: the lowest inverted
  // element, and if there is none the energy, internal force and K_fp du_p summed over the processes' elements.
  void sum_element_parts(Eval& ev, bool want_force, Eigen::VectorXd* kdup);
  // The split preconditioner's bulk term (split_preconditioned_solve.hpp) into the tangent's preconditioner values.
  void add_bulk_preconditioner();
  Eigen::VectorXd free_residual() const;
  // The failure of an evaluation that found an inverted element: which element, where in the reference mesh.
  Failure inverted(const Eval& ev) const;
  double tip_value(const Needle& nd, double disp) const { return -std::max(0.0, disp - nd.gap); }
  void add_free(Eigen::VectorXd& uu, const Eigen::VectorXd& du, double alpha) const;
  // StepResult::min_volume_ratio at the current displacement (a loop over every element: once per advance_to).
  double smallest_volume_ratio() const;
  // Forces, pressures and flags of the converged state (fint/fcontact of the last evaluation).
  void measure(StepResult& res);

  // ---- load steps (newton_step.cpp) ----
  bool solve_iteration(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing,
                       StepResult& res, Failure& failure);
  bool newton(double disp, StepResult& res, Failure& failure, int cutbacks_so_far);
  struct NewtonState;  // what one Newton solve carries from iteration to iteration (newton_step.cpp)
  double newton_line_search(double disp, const Eigen::VectorXd& du, double slope, bool expect_last, NewtonState& state,
                            IterationRecord& rec);
  // solve_iteration for Newton's direction at (u, disp); when the tangent cannot be factorized, once per Newton solve,
  // again with the contact tangent's curvature modified (SurfaceContact::set_positive_curvature).
  bool newton_direction(double disp, const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                        double forcing, StepResult& res, Failure& failure, NewtonState& state);
  // `predict`: false when u already holds a start (advance_to's warm start) that the predictor must not move.
  bool substep(double target, StepResult& res, Failure& failure, int cutbacks_so_far, bool predict = true);
  bool solve_substep(double target, StepResult& res, Failure& failure, int cutbacks_so_far, bool predict,
                     bool extrapolate);
  // From a start u out of balance at needle displacement `target` (a rezoned mesh's transferred state, whose Newton
  // did not converge directly): the residual r0 of the start is applied as a load and taken off in stages, s = 1 -> 0,
  // each a substep at the fixed needle with cut-backs of the stage (a homotopy on the out-of-balance force: natural-
  // parameter continuation, Allgower & Georg, Numerical Continuation Methods, 1990, ch. 1). The
  // start is in balance at s = 1 by construction, so no stage begins far from its solution and none begins inverted.
  bool ease_into_balance(double target, StepResult& res, Failure& failure);
  // A converged substep to needle displacement `next` from the state u_before: the predictor's increments, the
  // external work and the forces of the converged state.
  void accept_substep(double next, const Eigen::VectorXd& u_before);
  // advance's substep to `target` from a given start (QuasiStaticSolver::advance_to with a start): Newton from it,
  // else the start eased into balance; `why_not` says why each failed.
  bool substep_from_start(double target, const std::vector<Eigen::Vector3d>& start,
                          const detail::SurfaceContact::Multipliers& multipliers, StepResult& res, Failure& failure,
                          std::string& why_not);
  StepResult advance(double target, const std::vector<Eigen::Vector3d>* start, bool reload = true);
};

}  // namespace needlekit::fem
