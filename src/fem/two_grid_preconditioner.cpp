#include "two_grid_preconditioner.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "sparse_cholesky.hpp"

namespace needlekit::fem::detail {

namespace {

// A_c = P^T K P couples the coarse nodes that interpolate the nodes of one fine element: one group per element
// (compressed: group k holds nodes[pointers[k] .. pointers[k + 1])).
void coarse_element_groups(const TangentInputs& inputs, std::vector<int>& pointers, std::vector<int>& nodes) {
  const mesh::CoarseLevel& coarse = *inputs.coarse;
  const int nodes_per_element = inputs.nodes_per_element;
  const size_t elements = inputs.connectivity.size() / static_cast<size_t>(nodes_per_element);
  pointers.assign(1, 0);
  pointers.reserve(elements + 1);
  nodes.reserve(elements * 6);
  std::vector<int> group;
  for (size_t e = 0; e < elements; ++e) {
    group.clear();
    for (int a = 0; a < nodes_per_element; ++a) {
      const mesh::NodeInterpolation& parents = coarse.interpolation[static_cast<size_t>(
          inputs.connectivity[e * static_cast<size_t>(nodes_per_element) + a])];
      for (size_t k = 0; k < 4; ++k)
        if (parents.weights[k] != 0) group.push_back(parents.nodes[k]);
    }
    std::sort(group.begin(), group.end());
    group.erase(std::unique(group.begin(), group.end()), group.end());
    nodes.insert(nodes.end(), group.begin(), group.end());
    pointers.push_back(static_cast<int>(nodes.size()));
  }
}

}  // namespace

TwoGridPreconditioner::TwoGridPreconditioner(const TangentInputs& inputs, const UpperPattern& fine,
                                             tbb::task_arena& arena, int chebyshev_degree)
    : fine_(fine), arena_(arena), degree_(chebyshev_degree) {
  const int coarse_count = build_interpolation(inputs);
  build_restriction(coarse_count);
  build_neighbours();
  std::vector<int> group_pointers, group_nodes;
  coarse_element_groups(inputs, group_pointers, group_nodes);
  coarse_pattern_ = upper_pattern({}, 4, inputs.coarse->nodes, coarse_free_, &group_pointers, &group_nodes);
  coarse_values_.assign(coarse_pattern_.row_indices.size(), 0.0);
  coarse_cholesky_ = std::make_unique<SparseCholesky>(static_cast<int64_t>(coarse_count),
                                                      coarse_pattern_.column_pointers, coarse_pattern_.row_indices);
}

int TwoGridPreconditioner::build_interpolation(const TangentInputs& inputs) {
  const mesh::CoarseLevel& coarse = *inputs.coarse;
  const std::vector<int>& free_index = inputs.free_index;
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
  coarse_free_.assign(free_weight.size(), -1);
  int coarse_count = 0;
  for (size_t dof = 0; dof < coarse_free_.size(); ++dof)
    if (free_weight[dof] > 0.5 * all_weight[dof]) coarse_free_[dof] = coarse_count++;
  interpolation_.resize(fine_.column_pointers.size() - 1);
  for (size_t dof = 0; dof < free_index.size(); ++dof) {
    const int f = free_index[dof];
    if (f < 0) continue;
    const mesh::NodeInterpolation& parents = coarse.interpolation[dof / 3];
    Interpolation& row = interpolation_[static_cast<size_t>(f)];
    for (size_t k = 0; k < 4; ++k)
      if (parents.weights[k] != 0) {
        row.coarse[k] = coarse_free_[static_cast<size_t>(3 * parents.nodes[k]) + dof % 3];
        row.weight[k] = parents.weights[k];
      }
  }
  return coarse_count;
}

void TwoGridPreconditioner::build_restriction(int coarse_count) {
  std::vector<int32_t> count(static_cast<size_t>(coarse_count) + 1, 0);
  for (const Interpolation& row : interpolation_)
    for (int k = 0; k < 4; ++k)
      if (row.coarse[k] >= 0) ++count[static_cast<size_t>(row.coarse[k]) + 1];
  for (size_t c = 0; c + 1 < count.size(); ++c) count[c + 1] += count[c];
  restriction_pointers_ = count;
  restriction_.resize(static_cast<size_t>(count.back()));
  for (size_t f = 0; f < interpolation_.size(); ++f)
    for (int k = 0; k < 4; ++k)
      if (interpolation_[f].coarse[k] >= 0)
        restriction_[static_cast<size_t>(count[static_cast<size_t>(interpolation_[f].coarse[k])]++)] = {
            static_cast<int32_t>(f), interpolation_[f].weight[k]};
}

void TwoGridPreconditioner::build_neighbours() {
  const size_t fine_free = fine_.column_pointers.size() - 1;
  std::vector<int64_t> degree(fine_free + 1, 0);
  for (size_t c = 0; c < fine_free; ++c)
    for (int64_t k = fine_.column_pointers[c]; k < fine_.column_pointers[c + 1]; ++k) {
      ++degree[c + 1];
      if (fine_.row_indices[static_cast<size_t>(k)] != static_cast<int64_t>(c))
        ++degree[static_cast<size_t>(fine_.row_indices[static_cast<size_t>(k)]) + 1];
    }
  for (size_t f = 0; f < fine_free; ++f) degree[f + 1] += degree[f];
  neighbour_pointers_ = degree;
  neighbours_.resize(static_cast<size_t>(degree.back()));
  for (size_t c = 0; c < fine_free; ++c)
    for (int64_t k = fine_.column_pointers[c]; k < fine_.column_pointers[c + 1]; ++k) {
      const auto r = static_cast<int32_t>(fine_.row_indices[static_cast<size_t>(k)]);
      neighbours_[static_cast<size_t>(degree[c]++)] = {r, static_cast<int32_t>(k)};
      if (r != static_cast<int32_t>(c))
        neighbours_[static_cast<size_t>(degree[static_cast<size_t>(r)]++)] = {static_cast<int32_t>(c),
                                                                              static_cast<int32_t>(k)};
    }
}

TwoGridPreconditioner::~TwoGridPreconditioner() = default;

bool TwoGridPreconditioner::update(const std::vector<double>& values, const Multiply& multiply) {
  // Galerkin product A_c = P^T K P column by column: A_c(R, C) = Σ_{f interpolated from C} w_fC Σ_j K_jf Σ_R w_jR,
  // over the fine dofs j coupled to f (K's stored column f and row f), kept where R <= C. Each coarse column is
  // written by one task, its entries found through a dense map of its rows (no search): the same sums in the same
  // order whatever the number of threads.
  const int coarse_count = coarse_dofs();
  tbb::enumerable_thread_specific<std::vector<int64_t>> positions(
      [&] { return std::vector<int64_t>(static_cast<size_t>(coarse_count), -1); });
  arena_.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, coarse_count, 64), [&](const tbb::blocked_range<int>& range) {
      std::vector<int64_t>& position = positions.local();
      for (int column = range.begin(); column < range.end(); ++column) {
        const int64_t first = coarse_pattern_.column_pointers[static_cast<size_t>(column)];
        const int64_t last = coarse_pattern_.column_pointers[static_cast<size_t>(column) + 1];
        for (int64_t k = first; k < last; ++k) {
          position[static_cast<size_t>(coarse_pattern_.row_indices[static_cast<size_t>(k)])] = k;
          coarse_values_[static_cast<size_t>(k)] = 0;
        }
        for (int32_t q = restriction_pointers_[static_cast<size_t>(column)];
             q < restriction_pointers_[static_cast<size_t>(column) + 1]; ++q) {
          const Restriction& from = restriction_[static_cast<size_t>(q)];
          for (int64_t n = neighbour_pointers_[static_cast<size_t>(from.fine)];
               n < neighbour_pointers_[static_cast<size_t>(from.fine) + 1]; ++n) {
            const Neighbour& j = neighbours_[static_cast<size_t>(n)];
            const double v = from.weight * values[static_cast<size_t>(j.entry)];
            const Interpolation& pj = interpolation_[static_cast<size_t>(j.dof)];
            for (int a = 0; a < 4; ++a)
              if (pj.coarse[a] >= 0 && pj.coarse[a] <= column)
                coarse_values_[static_cast<size_t>(position[static_cast<size_t>(pj.coarse[a])])] += pj.weight[a] * v;
          }
        }
        for (int64_t k = first; k < last; ++k)
          position[static_cast<size_t>(coarse_pattern_.row_indices[static_cast<size_t>(k)])] = -1;
      }
    });
  });
  if (!coarse_cholesky_->factorize(coarse_values_)) return false;

  // Largest eigenvalue of D^-1 K: Rayleigh quotient after power iterations from a fixed pseudo-random start.
  set_smoother_diagonal(values);
  const int64_t n = static_cast<int64_t>(interpolation_.size());
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
