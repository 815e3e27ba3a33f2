// Internal: the direct strategies of linear_solve.hpp. LinearSolver::Cholesky takes a fresh CHOLMOD factorization of
// K per solve; LinearSolver::CholeskyCg runs CG preconditioned by the last factorization while that costs less than
// a fresh one (the balance is estimated from the pattern, not timed, so that a run does not depend on the machine's
// load). With a tangent that is not positive definite the diagonal is raised until it factorizes.
#pragma once
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "conjugate_gradients.hpp"
#include "linear_solve.hpp"
#include "sparse_cholesky.hpp"

namespace needlekit::fem::detail {

// Factorizes `values` (on `cholesky`'s pattern), raising the diagonal by growing fractions if it is not positive
// definite (a shifted Newton step is still a descent direction). False if even the largest shift fails.
bool factorize_or_shift(SparseCholesky& cholesky, const std::vector<double>& values, const UpperPattern& pattern);
// x = A^-1 r with the last factorization.
Eigen::VectorXd factor_solution(SparseCholesky& cholesky, const Eigen::VectorXd& r);
// CG iterations on the last factor worth trying before a factorization is cheaper, within [1, cap], for a matrix
// with `matrix_entries` stored entries.
int reuse_budget(const SparseCholesky& cholesky, size_t matrix_entries, int cap);

// What the strategies on a CHOLMOD factor (this one and split_preconditioned_solve.hpp) share: the factor of K or of
// a preconditioner matrix on `factor_pattern`, CG on it, and its statistics.
class FactorSolve : public LinearSolve {
public:
  std::string failure_reason() const override { return "the tangent matrix could not be factorized"; }
  double factor_nonzeros() const override { return cholesky_.factor_nonzeros(); }
  double factor_flops() const override { return cholesky_.factor_flops(); }

protected:
  FactorSolve(TangentMatrix& matrix, const SolverOptions& options, const UpperPattern& factor_pattern);
  // CG iterations on the last factor worth trying before a factorization is cheaper (reuse_budget).
  int reuse_iterations() const;

  TangentMatrix& matrix_;
  const SolverOptions& options_;
  SparseCholesky cholesky_;
  ConjugateGradients cg_;
  bool have_factor_ = false;
  int last_cg_iterations_ = 0;  // of the last CG solve
};

class CholeskySolve final : public FactorSolve {
public:
  // `reuse_factor`: CholeskyCg (CG on the last factor while worth it); false: Cholesky.
  CholeskySolve(TangentMatrix& matrix, const SolverOptions& options, bool reuse_factor)
      : FactorSolve(matrix, options, matrix.pattern()), reuse_factor_(reuse_factor) {}
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double forcing) override;

private:
  const bool reuse_factor_;
};

}  // namespace needlekit::fem::detail
