#include "cholesky_solve.hpp"

#include <algorithm>

namespace needlekit::fem::detail {
namespace {

// Cost balance of the reused factorization: CG on the last factor is worth it while its iterations cost less than
// a fresh factorization. A factorization takes CHOLMOD's flop count, a CG iteration 4 (nnz(L) + nnz(K)) flops (two
// triangular solves and the symmetric product), and a factorization's flops run kFactorFlopSpeedup times faster
// (dense BLAS-3 kernels against memory-bound triangular solves; measured 6.6 and 7.5 on the 100k- and 300k-tet
// skin blocks of BENCHMARKS.md).
constexpr double kFactorFlopSpeedup = 7.0;

}  // namespace

bool factorize_or_shift(SparseCholesky& cholesky, const std::vector<double>& values, const UpperPattern& pattern) {
  if (cholesky.factorize(values)) return true;
  std::vector<double> shifted = values;
  for (double beta : {1e-6, 1e-4, 1e-2, 1e-1, 1.0}) {
    shift_diagonal(pattern, values, beta, shifted);
    if (cholesky.factorize(shifted)) return true;
  }
  return false;
}

Eigen::VectorXd factor_solution(SparseCholesky& cholesky, const Eigen::VectorXd& r) {
  const std::vector<double> b(r.data(), r.data() + r.size());
  const auto x = cholesky.solve(b);
  return Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
}

int reuse_budget(const SparseCholesky& cholesky, size_t matrix_entries, int cap) {
  const double cg_flops = 4.0 * (cholesky.factor_nonzeros() + static_cast<double>(matrix_entries));
  return static_cast<int>(
      std::clamp(cholesky.factor_flops() / (kFactorFlopSpeedup * cg_flops), 1.0, static_cast<double>(cap)));
}

FactorSolve::FactorSolve(TangentMatrix& matrix, const SolverOptions& options, const UpperPattern& factor_pattern)
    : matrix_(matrix),
      options_(options),
      cholesky_(matrix.free_count(), factor_pattern.column_pointers, factor_pattern.row_indices),
      cg_(matrix) {}

int FactorSolve::reuse_iterations() const {
  return reuse_budget(cholesky_, matrix_.values().size(), options_.max_reuse_iterations);
}

// CG preconditioned by the last factorization when allowed, else (or on failure) a fresh factorization (with a
// diagonal shift if K is not positive definite).
bool CholeskySolve::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing) {
  // CG on the old factor, unless the last CG solve cost more than half a factorization: then refactorize now
  // rather than after a failed CG.
  const int budget = reuse_iterations();
  if (reuse_factor_ && have_factor_ && 2 * last_cg_iterations_ <= budget) {
    int its = 0;
    const double tol = std::max(forcing, options_.linear_tolerance);
    const auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = factor_solution(cholesky_, r); };
    if (cg_.solve(rhs, du, its, tol, budget, precondition)) {
      last_cg_iterations_ = its;
      rec.linear_iterations = its;
      cg_.remember(du);
      return true;
    }
  }
  last_cg_iterations_ = 0;
  rec.factorized = true;
  rec.linear_iterations = 0;
  have_factor_ = false;
  if (!factorize_or_shift(cholesky_, matrix_.values(), matrix_.pattern())) return false;
  have_factor_ = true;
  du = factor_solution(cholesky_, rhs);
  cg_.remember(du);
  return du.allFinite();
}

}  // namespace needlekit::fem::detail
