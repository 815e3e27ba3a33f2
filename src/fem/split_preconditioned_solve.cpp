#include "split_preconditioned_solve.hpp"

#include <algorithm>
#include <vector>

#include "conjugate_gradients.hpp"

namespace needlekit::fem::detail {
namespace {

// CG iterations allowed on a fresh factor of P before its diagonal shift. P^-1 K has its spectrum in about
// [μ/(λ+μ), 1] (P's element bulk term bounds the nodal one from above): about 50 at ν = 0.49 and 500 at ν = 0.499,
// i.e. some 20-70 iterations at the Newton forcing terms.
constexpr int kSplitMaxIterations = 400;

}  // namespace

// CG on K preconditioned by the factor of P: first on the last factor, while its solves cost no more than those on a
// fresh one plus half the CG iterations a factorization is worth; then on a fresh factor. If CG still fails (K not
// positive definite: CG meets a direction of non-positive curvature), the diagonals of K and P are raised by growing
// fractions, as for a failed factorization: a shifted Newton step is still a descent direction.
bool SplitPreconditionedSolve::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                     double forcing) {
  const double tol = std::max(forcing, options_.linear_tolerance);
  const auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = factor_solution(cholesky_, r); };
  const int budget = reuse_iterations();
  int its = 0;
  rec.linear_iterations = 0;
  if (have_factor_ && 2 * last_cg_iterations_ <= 2 * fresh_cg_iterations_ + budget) {
    if (cg_.solve(rhs, du, its, tol, fresh_cg_iterations_ + budget, precondition)) {
      rec.linear_iterations = last_cg_iterations_ = its;
      cg_.remember(du);
      return true;
    }
    rec.linear_iterations = its;
  }
  rec.factorized = true;
  std::vector<double>& pre_values = matrix_.preconditioner_values();
  const UpperPattern& pre_pattern = matrix_.preconditioner_pattern();
  have_factor_ = factorize_or_shift(cholesky_, pre_values, pre_pattern);
  bool ok = have_factor_ && cg_.solve(rhs, du, its, tol, kSplitMaxIterations, precondition);
  rec.linear_iterations += its;
  if (!ok) {
    const std::vector<double> unshifted_pre = pre_values;
    const auto shift_p = [&](double beta) {  // P with the same shift as K
      shift_diagonal(pre_pattern, unshifted_pre, beta, pre_values);
      return factorize_or_shift(cholesky_, pre_values, pre_pattern);
    };
    ok = cg_.shifted_solve(rhs, du, rec, tol, kSplitMaxIterations, its, shift_p, precondition);
    have_factor_ = false;  // a factor of a shifted P
    pre_values = unshifted_pre;
  }
  if (!ok) return false;
  fresh_cg_iterations_ = last_cg_iterations_ = its;
  cg_.remember(du);
  return true;
}

}  // namespace needlekit::fem::detail
