// Load steps of the quasi-static solver: the predictor (linearised elastic solution, §3.4, or the secant
// extrapolation of the last step), Newton's method with a backtracking line search on the total potential energy,
// the augmented-Lagrangian loop of surface contact (with its friction bounds), and the cut-back of failed steps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "needlekit/fem/line_search.hpp"
#include "quasi_static_solver_impl.hpp"

namespace needlekit::fem {
namespace {

// Inexact Newton: CG's relative tolerance for the first Newton iteration of a (sub)step and for the linearised
// predictor (a looser predictor costs Newton iterations: at 0.1, two-grid CG stopped after one iteration and the
// first step of a nearly incompressible T10 punch took 6 Newton solves instead of 5), and its upper bound.
constexpr double kFirstForcing = 1e-3;
constexpr double kMaxForcing = 1e-1;

std::string fmt_um(double m) {
  std::ostringstream s;
  s.precision(6);
  s << m * 1e6 << " um";
  return s.str();
}

// The norm of the free dofs of u.
double free_norm(const Eigen::VectorXd& u, const std::vector<int>& free_dofs) {
  double sum = 0;
  for (int dof : free_dofs) sum += u[dof] * u[dof];
  return std::sqrt(sum);
}

// Adds a finished iteration to the step's record.
void book(const IterationRecord& rec, StepResult& res) {
  res.iterations.push_back(rec);
  res.newton_iterations++;
  res.assembly_seconds += rec.assembly_seconds;
  res.solve_seconds += rec.solve_seconds;
}

}  // namespace

// One iteration's linear solve (predictor or Newton), timed and counted into `rec` and `res`.
bool QuasiStaticSolver::Impl::solve_iteration(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                              double forcing, StepResult& res, Failure& failure) {
  const auto t0 = Clock::now();
  if (!linear_solve->solve(rhs, du, rec, forcing)) {
    failure = {StepStatus::LinearSolverFailure, linear_solve->failure_reason()};
    return false;
  }
  rec.solve_seconds = seconds_since(t0);
  rec.increment_norm = du.norm();
  if (rec.factorized) res.factorizations++;
  return true;
}

// What one Newton solve carries from iteration to iteration.
struct QuasiStaticSolver::Impl::NewtonState {
  double first_energy_norm = 0;
  double last_du = std::numeric_limits<double>::infinity(), last_en = std::numeric_limits<double>::infinity();
  // Forces and tangent at u: assembled by the loop for the first iteration, afterwards by the line search's full-step
  // trial when that step is accepted (the usual case), so an accepted full step costs one assembly, not two. The
  // full-step trial leaves the tangent out when it expects Newton to stop there (tangent_ready false): the tangent
  // is then assembled only if the test fails after all.
  bool assembled = false, tangent_ready = false;
  double carried_assembly_seconds = 0, previous_residual = 0;
  // Surface contact: the iteration at which the set of nodes in contact last changed (contact cycling when Newton
  // fails while it keeps changing).
  size_t active_set = 0;
  int last_set_change = 0;
  bool positive_curvature = false;  // the contact tangent's curvature modified (after a failed factorization)
  Eval ev;
};

namespace {

// Why Newton ran out of iterations: contact cycling when the contact nodes changed within the last two iterations.
std::string iteration_limit_reason(int max_iterations, double relative_residual, bool cycling) {
  const std::string residual = "(residual " + std::to_string(relative_residual) +
                               " of the force scale; [solver] max_iterations sets the limit)";
  return "Newton did not converge in " + std::to_string(max_iterations) + " iterations " +
         (cycling ? "while the contact nodes kept changing " : "") + residual;
}

// Forcing term (Eisenstat & Walker 1996, choice 2): eta = (|r_k| / |r_k-1|)^2, at most kMaxForcing, and no tighter
// than leaving a tenth of the convergence target. Loose while far from the solution, tight near it, without spoiling
// Newton's quadratic convergence. (std::min/max, not std::clamp: the lower bound exceeds kMaxForcing once the
// residual is below its target and Newton still iterates for the displacement or energy test.)
double forcing_term(double residual, double previous_residual, double residual_target) {
  const double suggested = previous_residual > 0 ? std::pow(residual / previous_residual, 2) : kFirstForcing;
  return std::min(kMaxForcing, std::max(suggested, 0.1 * residual_target / residual));
}

}  // namespace

// The backtracking line search on the total potential along du; returns the step length. The full step's evaluation
// assembles the tangent too (the next iteration's assembly when the full step is accepted), unless Newton is
// expected to stop there (expect_last). Records in rec whether the search failed.
double QuasiStaticSolver::Impl::newton_line_search(double disp, const Eigen::VectorXd& du, double slope,
                                                   bool expect_last, NewtonState& state, IterationRecord& rec) {
  Eigen::VectorXd trial;
  const auto potential_at = [&](double a) {
    trial = u;
    add_free(trial, du, a);
    const auto t1 = Clock::now();
    const Eval e = evaluate(trial, disp, a >= 1, a == 1 && !expect_last);
    if (a == 1) state.carried_assembly_seconds = seconds_since(t1);
    LineSearchPoint point{e.valid, e.potential(), 0.0};
    if (a >= 1 && e.valid) point.slope = free_residual().dot(du);
    if (a == 1) state.ev = e;
    return point;
  };
  const LineSearchResult search = line_search(state.ev.potential(), slope, potential_at);
  state.assembled = search.step == 1 && search.last_evaluation_at_step;  // the full step, accepted without expansion
  state.tangent_ready = !expect_last;
  rec.line_search_failed = search.failed;
  return search.step;
}

bool QuasiStaticSolver::Impl::newton_direction(double disp, const Eigen::VectorXd& rhs, Eigen::VectorXd& du,
                                               IterationRecord& rec, double forcing, StepResult& res,
                                               Failure& failure, NewtonState& state) {
  if (solve_iteration(rhs, du, rec, forcing, res, failure)) return true;
  // An indefinite contact tangent (the second pass's curvature): the rest of this Newton solve with the curvature's
  // positive part (slower, but a descent direction). The residual at u is the same.
  if (!contact || state.positive_curvature || !contact->set_positive_curvature(true)) return false;
  state.positive_curvature = true;
  state.ev = evaluate(u, disp, true, true);
  return solve_iteration(rhs, du, rec, forcing, res, failure);
}

// Newton with backtracking line search at fixed needle displacement `disp` (and fixed multipliers).
bool QuasiStaticSolver::Impl::newton(double disp, StepResult& res, Failure& failure, int cutbacks_so_far) {
  const double tiny = 1e-14 * space.mean_youngs_modulus * space.mean_element_size * space.mean_element_size;
  NewtonState state;
  state.active_set = contact ? contact->active_set_fingerprint() : 0;
  if (contact) contact->set_positive_curvature(false);
  const int max_iterations = newton_iteration_limit(opt);
  for (int it = 1; it <= max_iterations + 1; ++it) {
    IterationRecord rec;
    auto t0 = Clock::now();
    if (!state.assembled) {
      state.ev = evaluate(u, disp, true, true);
      state.tangent_ready = true;
    }
    rec.assembly_seconds = state.assembled ? state.carried_assembly_seconds : seconds_since(t0);
    state.assembled = false;
    if (!state.ev.valid) {
      failure = inverted(state.ev);
      failure.start_inverted = it == 1;
      return false;
    }
    if (contact) {
      const size_t now = contact->active_set_fingerprint();
      if (now != state.active_set) state.last_set_change = it;
      state.active_set = now;
    }
    const Eigen::VectorXd r = free_residual();
    rec.residual_norm = r.norm();
    if (!std::isfinite(rec.residual_norm)) {
      failure = {StepStatus::IterationLimit, "the residual is not finite"};
      return false;
    }
    const double ref = std::max({fint.norm(), opt.contact == ContactModel::Surface ? fcontact.norm() : 0.0, tiny});
    const double unorm = free_norm(u, dofs.free_dofs);
    const bool res_ok = rec.residual_norm <= opt.residual_tolerance * ref;
    const bool disp_ok = state.last_du <= opt.displacement_tolerance * std::max(unorm, 1e-300);
    const bool energy_ok = it > 1 && state.last_en <= opt.energy_tolerance * state.first_energy_norm;
    if (rec.residual_norm <= tiny * 1e-6 || (res_ok && (disp_ok || energy_ok))) {
      converged_strain_energy = state.ev.strain_energy;
      return true;
    }
    if (it > max_iterations) {
      const bool cycling = contact && state.last_set_change > it - 3;
      failure = {cycling ? StepStatus::ContactCycling : StepStatus::IterationLimit,
                 iteration_limit_reason(max_iterations, rec.residual_norm / ref, cycling)};
      return false;
    }
    if (!state.tangent_ready) {  // the last trial expected to stop here and left the tangent out
      const auto t1 = Clock::now();
      state.ev = evaluate(u, disp, true, true);
      rec.assembly_seconds += seconds_since(t1);
      state.tangent_ready = true;
    }
    Eigen::VectorXd du;
    const double eta = forcing_term(rec.residual_norm, state.previous_residual, opt.residual_tolerance * ref);
    state.previous_residual = rec.residual_norm;
    if (!newton_direction(disp, -r, du, rec, eta, res, failure, state)) return false;
    const double slope = r.dot(du);
    rec.energy_norm = std::abs(slope);
    if (it == 1) state.first_energy_norm = rec.energy_norm;
    double alpha = 1;
    if (opt.line_search && slope < 0) {
      // Newton is expected to stop at the full step when it passes the displacement (or energy) test and CG left at
      // most half the residual target (Newton's own remainder is of higher order): then its tangent would not be
      // used; in most load steps this saves the tangent of the last trial.
      const bool expect_last = eta * rec.residual_norm <= 0.5 * opt.residual_tolerance * ref &&
                               (rec.increment_norm <= opt.displacement_tolerance * unorm ||
                                (it > 1 && rec.energy_norm <= opt.energy_tolerance * state.first_energy_norm));
      alpha = newton_line_search(disp, du, slope, expect_last, state, rec);
    }
    rec.step_length = alpha;
    add_free(u, du, alpha);
    state.last_du = alpha * rec.increment_norm;
    state.last_en = alpha * rec.energy_norm;
    book(rec, res);
    if (opt.progress)
      opt.progress({disp, it, rec.residual_norm, cutbacks_so_far, augmentation, alpha, rec.linear_iterations,
                    state.last_set_change == it});
  }
  return false;
}

// One substep from the current converged state (u, d) to displacement `target`. When the secant predictor's start
// inverts an element, the substep starts again from the converged state (with §3.4's linearised predictor under
// tip-node contact, when it is on) before the caller cuts the step back: where the tissue under a sharp tip is nearly
// crushed, the extrapolation overshoots even for small steps (the §6.2 sharp bevel at 8 um, 20 steps to 200 um: every
// one of its 23 cut-backs to 118 um, where it stopped, was the extrapolated start's inversion, down to 0.3 um steps).
// Only without friction, whose converged state does not depend on the load path: with friction a cut-back also
// integrates the stick-slip history in finer steps (the frictional blunt bevel's F(400 um) on a 28 um mesh moved from
// 16.1 to 19.6 mN when its inverted starts were restarted instead of cut back).
bool QuasiStaticSolver::Impl::substep(double target, StepResult& res, Failure& failure, int cutbacks_so_far,
                                      bool predict) {
  const bool extrapolate = predict && opt.extrapolate_predictor && last_step != 0 && last_increment.size() == ndof;
  if (!extrapolate || opt.friction > 0) {
    return solve_substep(target, res, failure, cutbacks_so_far, predict, extrapolate);
  }
  const Eigen::VectorXd converged = u;
  if (solve_substep(target, res, failure, cutbacks_so_far, predict, true)) return true;
  if (!failure.start_inverted) return false;
  u = converged;
  return solve_substep(target, res, failure, cutbacks_so_far, predict, false);
}

// The substep from the predicted start: with `extrapolate` the secant predictor, the last converged state
// extrapolated to this step, quadratically through the last three converged states when there are three (Newton's
// divided differences in the needle displacement), else linearly. On the 100k-tetrahedron skin block the quadratic
// start leaves a residual ~20x smaller than the linear one.
bool QuasiStaticSolver::Impl::solve_substep(double target, StepResult& res, Failure& failure, int cutbacks_so_far,
                                            bool predict, bool extrapolate) {
  if (extrapolate) {
    const double h = target - d;
    const Eigen::VectorXd slope = last_increment / last_step;
    u += h * slope;
    if (earlier_step != 0 && earlier_increment.size() == ndof)
      u += (h * (h + last_step) / (last_step + earlier_step)) * (slope - earlier_increment / earlier_step);
  }
  if (opt.contact == ContactModel::TipNodes) {
    Eigen::VectorXd dup = Eigen::VectorXd::Zero(ndof);
    for (const auto& nd : needles)
      for (int a : nd.tip_nodes) {
        const int dof = 3 * a + 2;
        if (dofs.tip_dof[dof]) dup[dof] = tip_value(nd, target) - u[dof];
      }
    if (predict && !extrapolate && opt.linear_predictor && dup.squaredNorm() > 0) {
      // §3.4: first iterate = linear(ised) elastic solution: K_ff du_f = -(R_f + K_fp du_p).
      IterationRecord rec;
      auto t0 = Clock::now();
      Eigen::VectorXd kdup = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs.free_dofs.size()));
      const Eval ev = evaluate(u, target, true, true, &dup, &kdup);
      rec.assembly_seconds = seconds_since(t0);
      if (!ev.valid) {
        failure = inverted(ev);
        return false;
      }
      const Eigen::VectorXd r = free_residual();
      rec.residual_norm = r.norm();
      Eigen::VectorXd du;
      if (!solve_iteration(-(r + kdup), du, rec, kFirstForcing, res, failure)) return false;
      add_free(u, du, 1.0);
      book(rec, res);
    }
    u += dup;
    augmentation = 0;
    return newton(target, res, failure, cutbacks_so_far);
  }
  // Surface contact: Newton at fixed multipliers, then augmented-Lagrangian updates.
  for (int aug = 0;; ++aug) {
    augmentation = aug;
    if (!newton(target, res, failure, cutbacks_so_far)) return false;
    const double pen = contact->max_penetration();
    const bool settled = pen <= opt.penetration_tolerance * std::max(std::abs(target), contact->smallest_size()) &&
                         contact->friction_settled();
    if (settled || aug >= opt.max_augmentations) {
      contact->update_ahead(space.nodes, u, target);
      contact->commit_friction(space.nodes, u, target);
      return true;
    }
    contact->augment();
  }
}

std::string_view to_string(StepStatus status) { return name_of(kStepStatusNames, status); }
std::string_view to_string(StartBalance balance) { return name_of(kStartBalanceNames, balance); }

StepResult QuasiStaticSolver::advance_to(double target) { return impl_->advance(target, nullptr); }

StepResult QuasiStaticSolver::advance_to(double target, const std::vector<Eigen::Vector3d>& start, bool reload) {
  if (start.size() != impl_->u_nodes.size()) {
    throw std::invalid_argument("advance_to: a start of " + std::to_string(start.size()) + " nodes for a solver of " +
                                std::to_string(impl_->u_nodes.size()));
  }
  return impl_->advance(target, &start, reload);
}

bool QuasiStaticSolver::Impl::ease_into_balance(double target, StepResult& res, Failure& failure) {
  const Eval start = evaluate(u, target, true, false);
  if (!start.valid) {
    failure = inverted(start);
    return false;
  }
  start_residual = free_residual();
  double share = 1, stage = 0.5;  // the share of the start's residual still applied, and the next stage's decrement
  int cutbacks = 0, streak = 0;
  while (share > 0) {
    const double next = std::max(0.0, share - stage);
    const Eigen::VectorXd u_saved = u;
    const auto multipliers_saved = contact ? contact->multipliers() : detail::SurfaceContact::Multipliers{};
    start_share = next;
    if (solve_substep(target, res, failure, cutbacks, false, false)) {
      share = next;
      if (++streak >= 2) stage *= 2, streak = 0;  // as advance's recovery after a cut-back
      continue;
    }
    u = u_saved;
    if (contact) contact->set_multipliers(multipliers_saved);
    streak = 0;
    if (++cutbacks > opt.max_cutbacks) break;
    stage *= 0.5;
  }
  start_share = 0;
  start_residual.resize(0);
  if (share > 0) failure.why = "at " + std::to_string(share) + " of the start's residual: " + failure.why;
  return share == 0;
}

void QuasiStaticSolver::Impl::accept_substep(double next, const Eigen::VectorXd& u_before) {
  const double previous = d;
  d = next;
  earlier_increment = std::move(last_increment);
  earlier_step = last_step;
  last_increment = u - u_before;
  last_step = next - previous;
  StepResult probe;
  measure(probe);
  for (size_t k = 0; k < needles.size(); ++k)
    external_work += 0.5 * (last_force[k] + probe.indenter_force[k]) * (next - previous);  // trapezoid
  last_force = probe.indenter_force;
}

bool QuasiStaticSolver::Impl::substep_from_start(double target, const std::vector<Eigen::Vector3d>& start,
                                                 const detail::SurfaceContact::Multipliers& multipliers,
                                                 StepResult& res, Failure& failure, std::string& why_not) {
  const auto set_start = [&] {  // a state on this mesh: its fixed dofs are this run's
    for (int n = 0; n < static_cast<int>(start.size()); ++n) u.segment<3>(3 * n) = start[n];
    if (contact) contact->set_multipliers(multipliers);
  };
  set_start();
  // The start stands for a converged state at the target: which nodes lead and which faces hold the second pass's
  // points are those at the start (a rezoned tip sits in its valley's crease, just outside its faces).
  if (contact) contact->update_ahead(space.nodes, u, target);
  if (substep(target, res, failure, res.cutbacks, false)) {
    res.start_balance = StartBalance::Newton;
    return true;
  }
  why_not = failure.why;
  set_start();
  if (ease_into_balance(target, res, failure)) {
    res.start_balance = StartBalance::Eased;
    return true;
  }
  why_not += "; eased into balance from it: " + failure.why;
  return false;
}

StepResult QuasiStaticSolver::Impl::advance(double target, const std::vector<Eigen::Vector3d>* start, bool reload) {
  auto& m = *this;
  const auto t0 = Impl::Clock::now();
  StepResult res;
  if (!std::isfinite(target)) {
    res.status = StepStatus::InvalidTarget;
    res.reason = "the target displacement is not finite";
    res.indenter_displacement = m.d;
    return res;
  }
  double step = target - m.d;
  std::string warm_failure;  // why the given start did not converge
  int streak = 0;
  bool ok = true, stepped = false;
  while (ok && m.d != target) {
    const double next = std::abs(target - m.d) <= std::abs(step) * (1 + 1e-12) ? target : m.d + step;
    const Eigen::VectorXd u_saved = m.u;
    const auto multipliers_saved = m.contact ? m.contact->multipliers() : detail::SurfaceContact::Multipliers{};
    Impl::Failure failure;
    const bool warm = start != nullptr && next == target;
    const bool done = warm ? m.substep_from_start(next, *start, multipliers_saved, res, failure, warm_failure)
                           : m.substep(next, res, failure, res.cutbacks);
    if (done) {
      m.accept_substep(next, u_saved);
      res.substeps++;
      stepped = true;
      if (++streak >= 2 && std::abs(step) < std::abs(target - m.d)) step *= 2, streak = 0;  // recover after cut-back
      if (std::abs(step) > std::abs(target - m.d) && m.d != target) step = target - m.d;
      continue;
    }
    m.u = u_saved;
    if (m.contact) m.contact->set_multipliers(multipliers_saved);
    if (warm && !reload) {
      res.status = failure.status;
      res.reason = "from the given start at " + fmt_um(target) + ": " + warm_failure;
      ok = false;
      break;
    }
    if (warm) {  // neither the start nor its easing converged: the ordinary step, predictor and cut-backs, from
                 // here on, with the contact history of the start (another mesh's, at the target) forgotten
      start = nullptr;
      res.start_balance = StartBalance::Reloaded;
      if (m.contact) m.contact->forget_history();
      continue;
    }
    streak = 0;
    if (res.cutbacks >= m.opt.max_cutbacks) {
      res.status = failure.status;
      res.reason = "stopped at " + fmt_um(m.d) + " (target " + fmt_um(target) + "): step to " + fmt_um(next) +
                   " failed after " + std::to_string(res.cutbacks) + " cut-backs: " + failure.why +
                   (warm_failure.empty() ? "" : "; from the given start at " + fmt_um(target) + ": " + warm_failure);
      ok = false;
      break;
    }
    res.cutbacks++;
    step *= 0.5;
  }
  // The outputs' forces are those of the last evaluation. After a converged substep under tip-node contact that was
  // Newton's at the converged state; otherwise (a failed or no substep, or surface contact, whose update_ahead moves
  // the contact frame after Newton) the state is evaluated again.
  const bool evaluated = ok && stepped && !m.contact;
  const double strain_energy = evaluated ? m.converged_strain_energy : m.evaluate(m.u, m.d, true, false).strain_energy;
  m.measure(res);
  res.min_volume_ratio = m.smallest_volume_ratio();  // once per call: not in measure(), which every substep's probe runs
  res.tip_embedded_depth = m.embedding ? m.embedding->deepest(m.space.nodes, m.u, m.d) : 0.0;
  res.converged = ok;
  if (ok) res.status = StepStatus::Converged;
  res.indenter_displacement = m.d;
  res.strain_energy = strain_energy;
  res.external_work = m.external_work;
  for (int n = 0; n < static_cast<int>(m.u_nodes.size()); ++n) m.u_nodes[n] = m.u.segment<3>(3 * n);
  res.total_seconds = Impl::seconds_since(t0);
  return res;
}

}  // namespace needlekit::fem
