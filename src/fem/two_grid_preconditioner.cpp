#include "two_grid_preconditioner.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "sparse_cholesky.hpp"

namespace needlekit::fem::detail {

TwoGridPreconditioner::TwoGridPreconditioner(const mesh::CoarseLevel& coarse, const std::vector<int>& free_index,
                                             const UpperPattern& fine, const std::vector<int>& connectivity,
                                             int nodes_per_element, int chebyshev_degree)
    : fine_(fine), degree_(chebyshev_degree) {
  // A coarse dof is kept when most of its interpolation weight goes to free fine dofs: one on a fixed face or under
  // a needle's tip nodes gives most of it to constrained fine dofs and is left out (as the fine dof of the same node
  // is in a nested level), which also keeps A_c regular where a coarse node reaches a single free fine dof.
  // Numbered in coarse dof order.
  std::vector<double> free_weight(static_cast<size_t>(3 * coarse.nodes), 0.0), all_weight(free_weight);
  for (size_t dof = 0; dof < free_index.size(); ++dof) {
    const mesh::NodeInterpolation& parents = coarse.interpolation[dof / 3];
    for (size_t k = 0; k < 4; ++k) {
      if (parents.weights[k] == 0) continue;
      const size_t coarse_dof = static_cast<size_t>(3 * parents.nodes[k]) + dof % 3;
      all_weight[coarse_dof] += parents.weights[k];
      if (free_index[dof] >= 0) free_weight[coarse_dof] += parents.weights[k];
    }
  }
  std::vector<int> coarse_free(free_weight.size(), -1);
  int coarse_count = 0;
  for (size_t dof = 0; dof < coarse_free.size(); ++dof)
    if (free_weight[dof] > 0.5 * all_weight[dof]) coarse_free[dof] = coarse_count++;
  const size_t fine_free = fine.column_pointers.size() - 1;
  interpolation_.resize(fine_free);
  for (size_t dof = 0; dof < free_index.size(); ++dof) {
    const int f = free_index[dof];
    if (f < 0) continue;
    const mesh::NodeInterpolation& parents = coarse.interpolation[dof / 3];
    Interpolation& row = interpolation_[static_cast<size_t>(f)];
    for (size_t k = 0; k < 4; ++k)
      if (parents.weights[k] != 0) {
        row.coarse[k] = coarse_free[static_cast<size_t>(3 * parents.nodes[k]) + dof % 3];
        row.weight[k] = parents.weights[k];
      }
  }
  // A_c = P^T K P couples the coarse nodes that interpolate the nodes of one fine element: one group per element.
  std::vector<int> group_pointers{0}, group_nodes;
  const size_t elements = connectivity.size() / static_cast<size_t>(nodes_per_element);
  group_pointers.reserve(elements + 1);
  group_nodes.reserve(elements * 6);
  std::vector<int> group;
  for (size_t e = 0; e < elements; ++e) {
    group.clear();
    for (int a = 0; a < nodes_per_element; ++a) {
      const mesh::NodeInterpolation& parents =
          coarse.interpolation[static_cast<size_t>(connectivity[e * static_cast<size_t>(nodes_per_element) + a])];
      for (size_t k = 0; k < 4; ++k)
        if (parents.weights[k] != 0) group.push_back(parents.nodes[k]);
    }
    std::sort(group.begin(), group.end());
    group.erase(std::unique(group.begin(), group.end()), group.end());
    group_nodes.insert(group_nodes.end(), group.begin(), group.end());
    group_pointers.push_back(static_cast<int>(group_nodes.size()));
  }
  coarse_pattern_ = upper_pattern({}, 4, coarse.nodes, coarse_free, &group_pointers, &group_nodes);
  coarse_values_.assign(coarse_pattern_.row_indices.size(), 0.0);
  coarse_cholesky_ = std::make_unique<SparseCholesky>(static_cast<int64_t>(coarse_count),
                                                      coarse_pattern_.column_pointers, coarse_pattern_.row_indices);
}

TwoGridPreconditioner::~TwoGridPreconditioner() = default;

bool TwoGridPreconditioner::update(const std::vector<double>& values, const Multiply& multiply) {
  // Galerkin product A_c = P^T K P over K's stored upper triangle: the entry (r, c) stands for K_rc and K_cr;
  // each adds w_r w_c K_rc to A_c(R, C) for the coarse dofs R of r and C of c, kept where R <= C. Two halves of
  // the columns in parallel, each into its own copy of the coarse values.
  const int64_t n = static_cast<int64_t>(fine_.column_pointers.size()) - 1;
  std::array<std::vector<double>, 2> partial;
  tbb::parallel_for(0, 2, [&](int half) {
    std::vector<double>& out = partial[static_cast<size_t>(half)];
    out.assign(coarse_values_.size(), 0.0);
    const auto add = [&](int coarse_row, int coarse_column, double v) {
      if (coarse_row < 0 || coarse_column < 0 || coarse_row > coarse_column) return;
      out[static_cast<size_t>(entry_position(coarse_pattern_, coarse_row, coarse_column))] += v;
    };
    const int64_t target = fine_.column_pointers.back() / 2;
    const int64_t middle = std::lower_bound(fine_.column_pointers.begin(), fine_.column_pointers.end(), target) -
                           fine_.column_pointers.begin();
    const int64_t c0 = half == 0 ? 0 : std::min(middle, n), c1 = half == 0 ? std::min(middle, n) : n;
    for (int64_t c = c0; c < c1; ++c) {
      const Interpolation& pc = interpolation_[static_cast<size_t>(c)];
      for (int64_t k = fine_.column_pointers[static_cast<size_t>(c)]; k < fine_.column_pointers[static_cast<size_t>(c) + 1]; ++k) {
        const int64_t r = fine_.row_indices[static_cast<size_t>(k)];
        const Interpolation& pr = interpolation_[static_cast<size_t>(r)];
        const double v = values[static_cast<size_t>(k)];
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b) {
            const double w = pr.weight[a] * pc.weight[b] * v;
            if (w == 0) continue;
            add(pr.coarse[a], pc.coarse[b], w);
            if (r != c) add(pc.coarse[b], pr.coarse[a], w);
          }
      }
    }
  });
  for (size_t i = 0; i < coarse_values_.size(); ++i) coarse_values_[i] = partial[0][i] + partial[1][i];
  if (!coarse_cholesky_->factorize(coarse_values_)) return false;

  // Largest eigenvalue of D^-1 K: Rayleigh quotient after power iterations from a fixed pseudo-random start.
  set_smoother_diagonal(values);
  Eigen::VectorXd x(n), kx;
  for (int64_t i = 0; i < n; ++i) x[i] = std::sin(1.0 + 12.9898 * static_cast<double>(i));
  double rayleigh = 0;
  for (int it = 0; it < 15; ++it) {
    multiply(x, kx);
    rayleigh = x.dot(kx) / x.dot(x.cwiseQuotient(inverse_diagonal_));
    x = inverse_diagonal_.cwiseProduct(kx);
    x /= x.norm();
  }
  lambda_max_ = rayleigh;
  return std::isfinite(lambda_max_) && lambda_max_ > 0;
}

void TwoGridPreconditioner::smooth(const Eigen::VectorXd& r, Eigen::VectorXd& x, const Multiply& multiply) {
  // Chebyshev iteration (Saad, Iterative Methods for Sparse Linear Systems, 2nd ed., Alg 12.1) for D^-1 K on
  // [a, b] = [0.1, 1.1] lambda_max, from x = 0: degree_ - 1 products with K.
  const double a = 0.1 * lambda_max_, b = 1.1 * lambda_max_;
  const double theta = 0.5 * (b + a), delta = 0.5 * (b - a), sigma = theta / delta;
  double rho = 1 / sigma;
  direction_ = inverse_diagonal_.cwiseProduct(r) / theta;
  x = direction_;
  for (int k = 1; k < degree_; ++k) {
    multiply(x, product_);
    smoother_residual_ = r - product_;
    const double rho_next = 1 / (2 * sigma - rho);
    direction_ = (rho_next * rho) * direction_ + (2 * rho_next / delta) * inverse_diagonal_.cwiseProduct(smoother_residual_);
    x += direction_;
    rho = rho_next;
  }
}

void TwoGridPreconditioner::set_smoother_diagonal(const std::vector<double>& values) {
  const int64_t n = static_cast<int64_t>(interpolation_.size());
  inverse_diagonal_.resize(n);
  for (int64_t c = 0; c < n; ++c)  // the diagonal is the last entry of each column
    inverse_diagonal_[c] = 1.0 / values[static_cast<size_t>(fine_.column_pointers[static_cast<size_t>(c) + 1] - 1)];
}

void TwoGridPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z, const Multiply& multiply) {
  const int64_t n = static_cast<int64_t>(interpolation_.size());
  // Pre-smoothing.
  smooth(r, z, multiply);
  // Coarse correction of the remaining residual.
  multiply(z, product_);
  residual_ = r - product_;
  std::vector<double> coarse_rhs(static_cast<size_t>(coarse_dofs()), 0.0);
  for (int64_t f = 0; f < n; ++f) {
    const Interpolation& p = interpolation_[static_cast<size_t>(f)];
    for (int k = 0; k < 4; ++k)
      if (p.coarse[k] >= 0) coarse_rhs[static_cast<size_t>(p.coarse[k])] += p.weight[k] * residual_[f];
  }
  const std::vector<double> coarse_solution = coarse_cholesky_->solve(coarse_rhs);
  for (int64_t f = 0; f < n; ++f) {
    const Interpolation& p = interpolation_[static_cast<size_t>(f)];
    for (int k = 0; k < 4; ++k)
      if (p.coarse[k] >= 0) z[f] += p.weight[k] * coarse_solution[static_cast<size_t>(p.coarse[k])];
  }
  // Post-smoothing.
  multiply(z, product_);
  residual_ = r - product_;
  smooth(residual_, correction_, multiply);
  z += correction_;
}

int TwoGridPreconditioner::coarse_dofs() const {
  return static_cast<int>(coarse_pattern_.column_pointers.size()) - 1;
}
double TwoGridPreconditioner::coarse_factor_nonzeros() const { return coarse_cholesky_->factor_nonzeros(); }
double TwoGridPreconditioner::coarse_factor_flops() const { return coarse_cholesky_->factor_flops(); }

}  // namespace needlekit::fem::detail
