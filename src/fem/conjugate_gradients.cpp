#include "conjugate_gradients.hpp"

#include <Eigen/Cholesky>

namespace needlekit::fem::detail {

void shift_diagonal(const UpperPattern& pattern, const std::vector<double>& base, double beta,
                    std::vector<double>& shifted) {
  for (size_t c = 0; c + 1 < pattern.column_pointers.size(); ++c) {
    const auto diagonal = static_cast<size_t>(pattern.column_pointers[c + 1] - 1);
    shifted[diagonal] = base[diagonal] * (1 + beta);
  }
}

void ConjugateGradients::remember(const Eigen::VectorXd& solution) {
  const double n = solution.norm();
  if (!(n > 0) || !solution.allFinite()) return;
  if (static_cast<int>(recycled_.size()) == kRecycled) recycled_.erase(recycled_.begin());
  recycled_.push_back(solution / n);
}

// CG starts from the Galerkin projection of the solution onto the recycled vectors W, x0 = W (W^T K W)^-1 W^T b,
// and only has to resolve what they miss.
void ConjugateGradients::recycled_start(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, Eigen::VectorXd& r) {
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
  matrix_.multiply(ws, kws);
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

}  // namespace needlekit::fem::detail
