// Internal: preconditioned conjugate gradients on the tangent (tangent_matrix.hpp) with Krylov recycling, and its
// retry with the diagonal raised when K is not positive definite: the Krylov part that the built-in linear solves
// (linear_solve.hpp) share.
#pragma once
#include <Eigen/Core>
#include <array>
#include <vector>

#include "needlekit/fem/solver_options.hpp"
#include "sparse_pattern.hpp"
#include "tangent_matrix.hpp"

namespace needlekit::fem::detail {

// Fractions by which the diagonal is raised when K is not positive definite (ConjugateGradients::shifted_solve).
inline constexpr std::array<double, 4> kDiagonalShifts{1e-4, 1e-2, 1e-1, 1.0};

// `shifted` = `base` with its diagonal raised by the fraction beta (for a tangent that is not positive definite);
// the off-diagonal entries of `shifted` are left as they are. The diagonal is the last entry of each column.
void shift_diagonal(const UpperPattern& pattern, const std::vector<double>& base, double beta,
                    std::vector<double>& shifted);

class ConjugateGradients {
public:
  explicit ConjugateGradients(TangentMatrix& matrix) : matrix_(matrix) {}

  // Preconditioned CG on the current values of K, started from the recycled solutions; false if it does not
  // converge in `budget` iterations (or meets a direction of non-positive curvature).
  template <class Preconditioner>
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int& iterations, double tolerance, int budget,
             Preconditioner&& precondition);

  // CG after it failed on a fresh preconditioner (K not positive definite): K's diagonal is raised by growing
  // fractions kDiagonalShifts[first], kDiagonalShifts[first + 1], ..., as for a failed factorization (a shifted
  // Newton step is still a descent direction), `refresh(beta)` rebuilds the preconditioner for the shifted K, and CG
  // is tried again. K's values are restored afterwards; the preconditioner, built for a shifted K, is stale. The
  // shift that worked is kept in shift_hint() (-1 when none did). Adds the CG iterations to `record`.
  template <class Refresh, class Preconditioner>
  bool shifted_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double tolerance,
                     int budget, int& iterations, Refresh&& refresh, Preconditioner&& precondition, int first = 0);
  int shift_hint() const { return shift_hint_; }

  // Adds a solution to the recycled ones (the last kRecycled, as unit vectors).
  void remember(const Eigen::VectorXd& solution);

private:
  // Krylov recycling: the last solutions span most of the next one (successive Newton corrections and load steps
  // deform the tissue alike).
  static constexpr int kRecycled = 12;
  void recycled_start(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, Eigen::VectorXd& r);

  TangentMatrix& matrix_;
  int shift_hint_ = -1;  // index into kDiagonalShifts of the last shifted solve's shift, -1: none (or none needed)
  // Unit vectors of the last solutions (newest last) and K times each (recomputed per solve).
  std::vector<Eigen::VectorXd> recycled_, recycled_products_;
};

template <class Preconditioner>
bool ConjugateGradients::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int& iterations, double tolerance,
                               int budget, Preconditioner&& precondition) {
  const double bnorm = rhs.norm();
  x = Eigen::VectorXd::Zero(rhs.size());
  if (bnorm == 0) return true;
  Eigen::VectorXd r = rhs;
  recycled_start(rhs, x, r);
  if (r.norm() <= tolerance * bnorm) {
    iterations = 0;
    return x.allFinite();
  }
  Eigen::VectorXd z, p, q;
  precondition(r, z);
  p = z;
  double rz = r.dot(z);
  for (iterations = 1; iterations <= budget; ++iterations) {
    matrix_.multiply(p, q);
    const double pq = p.dot(q);
    if (!(pq > 0)) return false;  // not positive definite along p
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    if (r.norm() <= tolerance * bnorm) return x.allFinite();
    precondition(r, z);
    const double rz_new = r.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
  return false;
}

template <class Refresh, class Preconditioner>
bool ConjugateGradients::shifted_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record,
                                       double tolerance, int budget, int& iterations, Refresh&& refresh,
                                       Preconditioner&& precondition, int first) {
  std::vector<double>& values = matrix_.values();
  const std::vector<double> unshifted = values;
  bool ok = false;
  shift_hint_ = -1;
  for (int shift = first; shift < static_cast<int>(kDiagonalShifts.size()) && !ok; ++shift) {
    const double beta = kDiagonalShifts[static_cast<size_t>(shift)];
    shift_diagonal(matrix_.pattern(), unshifted, beta, values);
    ok = refresh(beta) && solve(rhs, du, iterations, tolerance, budget, precondition);
    record.linear_iterations += iterations;
    if (ok) shift_hint_ = shift;
  }
  values = unshifted;  // the products of later solves use the tangent itself
  return ok;
}

}  // namespace needlekit::fem::detail
