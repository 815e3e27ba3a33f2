#include "two_grid_solve.hpp"

#include <algorithm>

namespace needlekit::fem::detail {
namespace {

constexpr int kTwoGridMaxIterations = 200;

}  // namespace

TwoGridSolve::TwoGridSolve(TangentMatrix& matrix, const TangentInputs& in, const SolverOptions& options,
                           tbb::task_arena& arena)
    : matrix_(matrix), options_(options), cg_(matrix) {
  if (!matrix.stores_patch_term())
    nodal_two_grid_ = std::make_unique<NodalVolumePreconditioner>(in, matrix.pattern(), matrix.product(), arena);
  else
    two_grid_ = std::make_unique<TwoGridPreconditioner>(in, matrix.pattern(), arena);
}

bool TwoGridSolve::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing) {
  const std::vector<double>& values = matrix_.values();
  if (nodal_two_grid_)
    return cycle_solve(
        rhs, du, rec, forcing,
        [&](bool renew) {
          if (renew) return nodal_two_grid_->update(values);
          nodal_two_grid_->refresh_smoother(values);
          return true;
        },
        [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { nodal_two_grid_->apply(r, z); });
  const auto multiply_k = [this](const Eigen::VectorXd& x, Eigen::VectorXd& y) { matrix_.multiply(x, y); };
  return cycle_solve(
      rhs, du, rec, forcing,
      [&](bool renew) {
        if (renew) return two_grid_->update(values, multiply_k);
        two_grid_->set_smoother_diagonal(values);  // K changed since the last solve; update() sets it itself
        return true;
      },
      [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { two_grid_->apply(r, z, multiply_k); });
}

// The coarse operator (and the smoother's spectral bound), `prepare(true)`, is renewed when missing, when the last
// solve needed more than two_grid_refresh_iterations, or when CG fails on a stale one; `prepare(false)` only follows
// the smoother's diagonal. If CG still fails (K not positive definite: SVK under strong compression, the §6.2 sharp
// bevel under its tip), the tangent's diagonal is raised by growing fractions, as for a failed factorization (a
// shifted Newton step is still a descent direction), on the same coarse operator: its factorization costs more than
// the extra CG iterations of a coarse level without the shift. After a solve that needed a shift, K is likely still
// indefinite: the next one starts one shift lower instead of from the unshifted K (on the sharp bevel the tangent
// needs the largest shift for several Newton iterations in a row: 11 coarse factorizations in its first three load
// steps became 2).
template <class Prepare, class Preconditioner>
bool TwoGridSolve::cycle_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing,
                               Prepare&& prepare, Preconditioner&& precondition) {
  const double tol = std::max(forcing, options_.linear_tolerance);
  int its = 0;
  rec.linear_iterations = 0;
  bool ok = false;
  const bool fresh_enough = have_factor_ && last_cg_iterations_ <= options_.two_grid_refresh_iterations;
  if (cg_.shift_hint() <= 0) {
    if (fresh_enough && prepare(false)) {
      if (cg_.solve(rhs, du, its, tol, kTwoGridMaxIterations, precondition)) {
        rec.linear_iterations = last_cg_iterations_ = its;
        cg_.remember(du);
        return true;
      }
      rec.linear_iterations = its;
    }
    rec.factorized = true;
    ok = (have_factor_ = prepare(true)) && cg_.solve(rhs, du, its, tol, kTwoGridMaxIterations, precondition);
    rec.linear_iterations += its;
  }
  if (!ok) {
    bool coarse_ready = have_factor_ && (rec.factorized || fresh_enough);
    rec.factorized = true;
    const auto refresh = [&](double) { return coarse_ready ? prepare(false) : (coarse_ready = prepare(true)); };
    ok = cg_.shifted_solve(rhs, du, rec, tol, kTwoGridMaxIterations, its, refresh, precondition,
                           std::max(cg_.shift_hint() - 1, 0));
    have_factor_ = coarse_ready;  // a coarse operator of a shifted K still serves the next (shifted) solve
  }
  last_cg_iterations_ = its;
  if (ok) cg_.remember(du);
  return ok;
}

double TwoGridSolve::factor_nonzeros() const {
  return nodal_two_grid_ ? nodal_two_grid_->coarse_factor_nonzeros() : two_grid_->coarse_factor_nonzeros();
}
double TwoGridSolve::factor_flops() const {
  return nodal_two_grid_ ? nodal_two_grid_->coarse_factor_flops() : two_grid_->coarse_factor_flops();
}

}  // namespace needlekit::fem::detail
