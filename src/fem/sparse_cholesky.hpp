// Internal: CHOLMOD behind a small interface (cholmod.h stays in sparse_cholesky.cpp). A symmetric matrix given by
// its upper triangle in compressed-column form with a fixed pattern: analysed once, factorized per call.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

namespace needlekit::fem::detail {

class SparseCholesky {
public:
  // Pattern: column pointers (n + 1) and sorted row indices (row <= column) of the upper triangle.
  SparseCholesky(int64_t n, const std::vector<int64_t>& column_pointers, const std::vector<int64_t>& row_indices);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Numeric factorization of the matrix with these values (same pattern). False if not positive definite.
  bool factorize(const std::vector<double>& values);
  // Solves A x = b with the last successful factorization.
  std::vector<double> solve(const std::vector<double>& b);
  double factor_nonzeros() const;
  double factor_flops() const;  // floating-point operations of one numeric factorization (from the analysis)

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace needlekit::fem::detail
