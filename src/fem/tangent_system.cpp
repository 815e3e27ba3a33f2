#include "tangent_system.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <limits>
#include <string>

#include "needlekit/core/errors.hpp"

namespace needlekit::fem::detail {
namespace {

// Cost balance of the reused factorization: CG on the last factor is worth it while its iterations cost less than
// a fresh factorization. The costs are estimated from the pattern, not timed, so that a run does not depend on the
// machine's load: a factorization takes CHOLMOD's flop count, a CG iteration 4 (nnz(L) + nnz(K)) flops (two
// triangular solves and the symmetric product), and a factorization's flops run kFactorFlopSpeedup times faster
// (dense BLAS-3 kernels against memory-bound triangular solves; measured 6.6 and 7.5 on the 100k- and 300k-tet
// skin blocks of BENCHMARKS.md).
constexpr double kFactorFlopSpeedup = 7.0;
// Krylov recycling: the last solutions span most of the next one (successive Newton corrections and load steps
// deform the tissue alike).
constexpr int kRecycled = 12;
constexpr int kTwoGridMaxIterations = 200;
// Split preconditioner: CG iterations allowed on a fresh factor of P before its diagonal shift. P^-1 K has its
// spectrum in about [μ/(λ+μ), 1] (P's element bulk term bounds the nodal one from above, tangent_system.hpp): about
// 50 at ν = 0.49 and 500 at ν = 0.499, i.e. some 20-70 iterations at the Newton forcing terms.
constexpr int kSplitMaxIterations = 400;
// Fractions by which the diagonal is raised when K is not positive definite (TangentSystem::shifted_cg_solve).
constexpr std::array<double, 4> kShifts{1e-4, 1e-2, 1e-1, 1.0};

}  // namespace

TangentSystem::TangentSystem(const std::vector<int>& conn, int nn, int node_count, const std::vector<int>& free_index,
                             const std::vector<int>& assembly_order, LinearSolver solver,
                             const mesh::CoarseLevel* coarse, const SolverOptions& options, tbb::task_arena& arena,
                             const NodalVolumeAverage* nodal)
    : options_(options), arena_(arena), solver_(solver), free_index_(free_index) {
  // The nodal average's patch term G D G^T: assembled into K (two-ring pattern) for the Cholesky solvers, applied
  // as a product for the two-grid one (K holds the one-ring element part A).
  if (nodal && solver_ == LinearSolver::TwoGrid) patch_term_ = nodal;
  const bool two_ring = nodal && !patch_term_;
  pattern_ = upper_pattern(conn, nn, node_count, free_index, two_ring ? &nodal->patch_pointers() : nullptr,
                           two_ring ? &nodal->patch_nodes() : nullptr);
  values_.assign(pattern_.row_indices.size(), 0.0);
  if (values_.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    throw InvalidInput("tissue mesh: the stiffness matrix has " + std::to_string(values_.size()) +
                       " entries, more than this solver indexes");
  product_ = std::make_unique<SymmetricProduct>(pattern_, arena_);
  const int k = 3 * nn;
  const size_t ne = conn.size() / static_cast<size_t>(nn);
  slots_per_element_ = static_cast<size_t>(upper_slots(k));
  value_slot_.assign(ne * slots_per_element_, -1);
  arena_.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 1024), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t position = range.begin(); position < range.end(); ++position) {
        const size_t e = static_cast<size_t>(assembly_order[position]);
        int32_t* slot = &value_slot_[position * slots_per_element_];
        for (int col = 0; col < k; ++col) {
          const int cb = free_index[3 * conn[e * nn + col / 3] + col % 3];
          for (int row = 0; row <= col; ++row, ++slot) {
            const int ra = free_index[3 * conn[e * nn + row / 3] + row % 3];
            if (ra < 0 || cb < 0) continue;
            *slot = static_cast<int32_t>(entry_position(pattern_, std::min(ra, cb), std::max(ra, cb)));
          }
        }
      }
    });
  });
  const int64_t free_count = static_cast<int64_t>(pattern_.column_pointers.size()) - 1;
  if (two_ring && solver_ == LinearSolver::CholeskyCg) {
    pre_pattern_ = upper_pattern(conn, nn, node_count, free_index);
    pre_values_.assign(pre_pattern_.row_indices.size(), 0.0);
    full_to_pre_.assign(values_.size(), -1);
    for (int64_t c = 0; c < free_count; ++c) {  // both patterns sorted per column, P's a subset of K's
      int64_t k = pattern_.column_pointers[static_cast<size_t>(c)];
      for (int64_t q = pre_pattern_.column_pointers[static_cast<size_t>(c)];
           q < pre_pattern_.column_pointers[static_cast<size_t>(c) + 1]; ++q) {
        while (pattern_.row_indices[static_cast<size_t>(k)] < pre_pattern_.row_indices[static_cast<size_t>(q)]) ++k;
        full_to_pre_[static_cast<size_t>(k)] = static_cast<int32_t>(q);
      }
    }
  }
  if (patch_term_)
    nodal_two_grid_ =
        std::make_unique<NodalVolumePreconditioner>(*coarse, free_index, pattern_, *product_, conn, *nodal, arena_);
  else if (solver_ == LinearSolver::TwoGrid)
    two_grid_ = std::make_unique<TwoGridPreconditioner>(*coarse, free_index, pattern_, conn, nn, arena_);
  else if (splits_preconditioner())
    cholesky_ = std::make_unique<SparseCholesky>(free_count, pre_pattern_.column_pointers, pre_pattern_.row_indices);
  else
    cholesky_ = std::make_unique<SparseCholesky>(free_count, pattern_.column_pointers, pattern_.row_indices);
}

void TangentSystem::capture_preconditioner() {
  for (size_t k = 0; k < values_.size(); ++k)
    if (full_to_pre_[k] >= 0) pre_values_[static_cast<size_t>(full_to_pre_[k])] = values_[k];
}

void TangentSystem::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  product_->multiply(values_, x, y);
  if (patch_term_) add_patch_product(x, y);
}

void TangentSystem::add_patch_product(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  patch_term_->gradient_transpose_product(free_index_, x, patch_values_, arena_);
  for (Eigen::Index a = 0; a < patch_values_.size(); ++a)
    patch_values_[a] *= patch_term_->node_curvature(static_cast<size_t>(a));
  patch_term_->add_gradient_product(free_index_, patch_values_, y, arena_);
}

// CG iterations worth trying before a factorization is cheaper, within [1, max_reuse_iterations].
int TangentSystem::cg_budget() const {
  const double cg_flops = 4.0 * (cholesky_->factor_nonzeros() + static_cast<double>(values_.size()));
  return static_cast<int>(std::clamp(cholesky_->factor_flops() / (kFactorFlopSpeedup * cg_flops), 1.0,
                                     static_cast<double>(options_.max_reuse_iterations)));
}

Eigen::VectorXd TangentSystem::apply_factor(const Eigen::VectorXd& r) {
  const std::vector<double> b(r.data(), r.data() + r.size());
  const auto x = cholesky_->solve(b);
  return Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
}

void TangentSystem::remember(const Eigen::VectorXd& solution) {
  const double n = solution.norm();
  if (!(n > 0) || !solution.allFinite()) return;
  if (static_cast<int>(recycled_.size()) == kRecycled) recycled_.erase(recycled_.begin());
  recycled_.push_back(solution / n);
}

// CG starts from the Galerkin projection of the solution onto the recycled vectors W, x0 = W (W^T K W)^-1 W^T b,
// and only has to resolve what they miss.
void TangentSystem::recycled_start(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, Eigen::VectorXd& r) {
  const int m = static_cast<int>(recycled_.size());
  if (m == 0) return;
  std::vector<Eigen::VectorXd>& kw = recycled_products_;
  kw.resize(static_cast<size_t>(m));
  Eigen::MatrixXd g(m, m);
  Eigen::VectorXd wb(m);
  std::vector<const Eigen::VectorXd*> ws(static_cast<size_t>(m));
  std::vector<Eigen::VectorXd*> kws(static_cast<size_t>(m));
  for (size_t i = 0; i < ws.size(); ++i) {
    ws[i] = &recycled_[i];
    kws[i] = &kw[i];
  }
  product_->multiply(values_, ws, kws);  // one pass over K per kMaxBlock vectors
  if (patch_term_)
    for (int i = 0; i < m; ++i) add_patch_product(recycled_[static_cast<size_t>(i)], kw[static_cast<size_t>(i)]);
  for (int i = 0; i < m; ++i) {
    wb[i] = recycled_[static_cast<size_t>(i)].dot(rhs);
    for (int j = 0; j < m; ++j) g(i, j) = recycled_[static_cast<size_t>(i)].dot(kw[static_cast<size_t>(j)]);
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(g);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return;
  const Eigen::VectorXd y = ldlt.solve(wb);
  if (!y.allFinite()) return;
  for (int i = 0; i < m; ++i) {
    x += y[i] * recycled_[static_cast<size_t>(i)];
    r -= y[i] * kw[static_cast<size_t>(i)];
  }
}

// Preconditioned CG on the current values; false if it does not converge in `budget` iterations.
template <class Preconditioner>
bool TangentSystem::cg_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int& iterations, double tolerance,
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
    multiply(p, q);
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

// `shifted` = `base` with its diagonal raised by the fraction beta (for a tangent that is not positive definite);
// the off-diagonal entries of `shifted` are left as they are. The diagonal is the last entry of each column.
void TangentSystem::shift_diagonal(const UpperPattern& pattern, const std::vector<double>& base, double beta,
                                   std::vector<double>& shifted) {
  for (size_t c = 0; c + 1 < pattern.column_pointers.size(); ++c) {
    const auto diagonal = static_cast<size_t>(pattern.column_pointers[c + 1] - 1);
    shifted[diagonal] = base[diagonal] * (1 + beta);
  }
}

bool TangentSystem::factorize_or_shift(SparseCholesky& cholesky, const std::vector<double>& values,
                                       const UpperPattern& pattern) {
  if (cholesky.factorize(values)) return true;
  std::vector<double> shifted = values;
  for (double beta : {1e-6, 1e-4, 1e-2, 1e-1, 1.0}) {
    shift_diagonal(pattern, values, beta, shifted);
    if (cholesky.factorize(shifted)) return true;
  }
  return false;
}

// CG after it failed on a fresh preconditioner (K not positive definite): K's diagonal is raised by growing fractions
// kShifts[first], kShifts[first + 1], ..., as for a failed factorization (a shifted Newton step is still a descent
// direction), `refresh(beta)` rebuilds the preconditioner for the shifted K, and CG is tried again. K's values are
// restored afterwards, and the preconditioner, built for a shifted K, is marked stale. The shift that worked is kept
// in shift_hint_ (-1 when none did).
template <class Refresh, class Preconditioner>
bool TangentSystem::shifted_cg_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                     double tolerance, int budget, int& iterations, Refresh&& refresh,
                                     Preconditioner&& precondition, int first) {
  const std::vector<double> unshifted = values_;
  bool ok = false;
  shift_hint_ = -1;
  for (int shift = first; shift < static_cast<int>(kShifts.size()) && !ok; ++shift) {
    const double beta = kShifts[static_cast<size_t>(shift)];
    shift_diagonal(pattern_, unshifted, beta, values_);
    ok = (have_factor_ = refresh(beta)) && cg_solve(rhs, du, iterations, tolerance, budget, precondition);
    rec.linear_iterations += iterations;
    if (ok) shift_hint_ = shift;
  }
  values_ = unshifted;  // the products of later solves use the tangent itself
  have_factor_ = false;
  return ok;
}

bool TangentSystem::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing) {
  if (solver_ == LinearSolver::TwoGrid) return two_grid_solve(rhs, du, rec, forcing);
  return splits_preconditioner() ? split_solve(rhs, du, rec, forcing) : cholesky_solve(rhs, du, rec, forcing);
}

// CG on K preconditioned by the factor of P: first on the last factor, while its solves cost no more than those on a
// fresh one plus half the CG iterations a factorization is worth; then on a fresh factor. If CG still fails (K not
// positive definite: CG meets a direction of non-positive curvature), the diagonals of K and P are raised by growing
// fractions, as for a failed factorization: a shifted Newton step is still a descent direction. K itself is never
// factorized (its two-ring factor is what this avoids).
bool TangentSystem::split_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                double forcing) {
  const double tol = std::max(forcing, options_.linear_tolerance);
  const auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = apply_factor(r); };
  const int budget = cg_budget();
  int its = 0;
  rec.linear_iterations = 0;
  if (have_factor_ && 2 * last_cg_iterations_ <= 2 * fresh_cg_iterations_ + budget) {
    if (cg_solve(rhs, du, its, tol, fresh_cg_iterations_ + budget, precondition)) {
      rec.linear_iterations = last_cg_iterations_ = its;
      remember(du);
      return true;
    }
    rec.linear_iterations = its;
  }
  rec.factorized = true;
  have_factor_ = factorize_or_shift(*cholesky_, pre_values_, pre_pattern_);
  bool ok = have_factor_ && cg_solve(rhs, du, its, tol, kSplitMaxIterations, precondition);
  rec.linear_iterations += its;
  if (!ok) {
    const std::vector<double> unshifted_pre = pre_values_;
    const auto shift_p = [&](double beta) {  // P with the same shift as K
      shift_diagonal(pre_pattern_, unshifted_pre, beta, pre_values_);
      return factorize_or_shift(*cholesky_, pre_values_, pre_pattern_);
    };
    ok = shifted_cg_solve(rhs, du, rec, tol, kSplitMaxIterations, its, shift_p, precondition);
    pre_values_ = unshifted_pre;
  }
  if (!ok) return false;
  fresh_cg_iterations_ = last_cg_iterations_ = its;
  remember(du);
  return true;
}

// CG preconditioned by the last factorization when allowed, else (or on failure) a fresh factorization (with a
// diagonal shift if K is not positive definite).
bool TangentSystem::cholesky_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                   double forcing) {
  // CG on the old factor, unless the last CG solve cost more than half a factorization: then refactorize now
  // rather than after a failed CG.
  const int budget = cg_budget();
  if (solver_ == LinearSolver::CholeskyCg && have_factor_ && 2 * last_cg_iterations_ <= budget) {
    int its = 0;
    const double tol = std::max(forcing, options_.linear_tolerance);
    const auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = apply_factor(r); };
    if (cg_solve(rhs, du, its, tol, budget, precondition)) {
      last_cg_iterations_ = its;
      rec.linear_iterations = its;
      remember(du);
      return true;
    }
  }
  last_cg_iterations_ = 0;
  rec.factorized = true;
  rec.linear_iterations = 0;
  have_factor_ = false;
  if (!factorize_or_shift(*cholesky_, values_, pattern_)) return false;
  have_factor_ = true;
  du = apply_factor(rhs);
  remember(du);
  return du.allFinite();
}

// CG with the two-grid cycle: on K itself, or with a nodal average the Woodbury form of nodal_volume_preconditioner.hpp
// whose cycle runs on the stored element part.
bool TangentSystem::two_grid_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec,
                                   double forcing) {
  if (nodal_two_grid_)
    return cycle_solve(
        rhs, du, rec, forcing,
        [&](bool renew) {
          if (renew) return nodal_two_grid_->update(values_);
          nodal_two_grid_->refresh_smoother(values_);
          return true;
        },
        [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { nodal_two_grid_->apply(r, z); });
  const auto multiply_k = [this](const Eigen::VectorXd& x, Eigen::VectorXd& y) { multiply(x, y); };
  return cycle_solve(
      rhs, du, rec, forcing,
      [&](bool renew) {
        if (renew) return two_grid_->update(values_, multiply_k);
        two_grid_->set_smoother_diagonal(values_);  // K changed since the last solve; update() sets it itself
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
bool TangentSystem::cycle_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing,
                                Prepare&& prepare, Preconditioner&& precondition) {
  const double tol = std::max(forcing, options_.linear_tolerance);
  int its = 0;
  rec.linear_iterations = 0;
  bool ok = false;
  const bool fresh_enough = have_factor_ && last_cg_iterations_ <= options_.two_grid_refresh_iterations;
  if (shift_hint_ <= 0) {
    if (fresh_enough && prepare(false)) {
      if (cg_solve(rhs, du, its, tol, kTwoGridMaxIterations, precondition)) {
        rec.linear_iterations = last_cg_iterations_ = its;
        remember(du);
        return true;
      }
      rec.linear_iterations = its;
    }
    rec.factorized = true;
    ok = (have_factor_ = prepare(true)) && cg_solve(rhs, du, its, tol, kTwoGridMaxIterations, precondition);
    rec.linear_iterations += its;
  }
  if (!ok) {
    bool coarse_ready = have_factor_ && (rec.factorized || fresh_enough);
    rec.factorized = true;
    const auto refresh = [&](double) { return coarse_ready ? prepare(false) : (coarse_ready = prepare(true)); };
    ok = shifted_cg_solve(rhs, du, rec, tol, kTwoGridMaxIterations, its, refresh, precondition,
                          std::max(shift_hint_ - 1, 0));
    have_factor_ = coarse_ready;  // a coarse operator of a shifted K still serves the next (shifted) solve
  }
  last_cg_iterations_ = its;
  if (ok) remember(du);
  return ok;
}

double TangentSystem::factor_nonzeros() const {
  if (nodal_two_grid_) return nodal_two_grid_->coarse_factor_nonzeros();
  return two_grid_ ? two_grid_->coarse_factor_nonzeros() : cholesky_->factor_nonzeros();
}
double TangentSystem::factor_flops() const {
  if (nodal_two_grid_) return nodal_two_grid_->coarse_factor_flops();
  return two_grid_ ? two_grid_->coarse_factor_flops() : cholesky_->factor_flops();
}

}  // namespace needlekit::fem::detail
