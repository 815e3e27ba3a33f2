// Internal: y = K x for the symmetric tangent stored as its upper triangle (UpperPattern, CSC with the diagonal last
// in each column), threaded, for one vector or a few at once. The solver's hot path: CG's products and the two-grid
// smoother's. The product is memory-bound, so several vectors at once (Krylov recycling's K W) read the matrix once
// for all of them.
//
// Threads: the columns are cut into a fixed number of ranges (kParts) of equal stored entries; each range scatters its
// transposed part into its own vector of partial sums (the symmetric product writes rows above the range), and the
// partial sums are added in range order. The number of ranges is fixed, not the number of threads, so that every
// product, and with it every solve, is bitwise the same whatever the number of threads; a product of several vectors
// gives each of them bitwise the single product.
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "sparse_pattern.hpp"

namespace needlekit::fem::detail {

class SymmetricProduct {
public:
  // Column ranges: enough for the cores of a workstation; each costs one vector of partial sums per product.
  static constexpr int kParts = 8;
  // The most vectors one pass takes (the partial sums grow with it).
  static constexpr int kMaxBlock = 4;

  // `pattern` must outlive the product; its row indices must fit 32 bits (the caller checks the entry count).
  SymmetricProduct(const UpperPattern& pattern, tbb::task_arena& arena);

  // y = K x, K's stored entries `values` on the pattern.
  void multiply(const std::vector<double>& values, const Eigen::VectorXd& x, Eigen::VectorXd& y);
  // ys[i] = K xs[i] for every i, in passes of up to kMaxBlock vectors.
  void multiply(const std::vector<double>& values, std::span<const Eigen::VectorXd* const> xs,
                std::span<Eigen::VectorXd* const> ys);

private:
  template <int Width>
  void pass(const std::vector<double>& values, const Eigen::VectorXd* const* xs, Eigen::VectorXd* const* ys);

  const UpperPattern& pattern_;
  tbb::task_arena& arena_;
  std::vector<int32_t> rows32_;  // the pattern's row indices as 32-bit: the product's memory traffic is a quarter less
  std::array<int64_t, kParts + 1> column_begin_{};  // range q: columns [column_begin_[q], column_begin_[q + 1])
  std::array<std::vector<double>, kParts> partial_;  // per range, row-interleaved partial sums (kept between calls)
};

}  // namespace needlekit::fem::detail
