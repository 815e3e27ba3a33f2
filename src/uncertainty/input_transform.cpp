#include "needlekit/uncertainty/input_transform.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::uncertainty {

double mass_outside_window(const UncertainInput& input) {
  const double below = std::isfinite(input.lower) ? cdf(input.distribution, input.lower) : 0.0;
  const double above = std::isfinite(input.upper) ? 1 - cdf(input.distribution, input.upper) : 0.0;
  return below + above;
}

InputTransform::InputTransform(std::vector<UncertainInput> inputs, const std::vector<Correlation>& correlations)
    : inputs_(std::move(inputs)) {
  for (const UncertainInput& input : inputs_) {
    validate(input.distribution, input.key);
    const double lo = std::isfinite(input.lower) ? cdf(input.distribution, input.lower) : 0.0;
    const double hi = std::isfinite(input.upper) ? cdf(input.distribution, input.upper) : 1.0;
    if (!(hi > lo)) {
      throw InvalidInput(fmt::format("{}: the distribution has no mass inside the physical range, expected values "
                                     "within it",
                                     input.key));
    }
    window_lo_.push_back(lo);
    window_hi_.push_back(hi);
  }
  const std::size_t k = inputs_.size();
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  for (const Correlation& c : correlations) {
    if (c.first >= k || c.second >= k || c.first == c.second) {
      throw InvalidInput("correlation: expected two different uncertain inputs");
    }
    const std::string pair = fmt::format("correlation between {} and {}", inputs_[c.first].key, inputs_[c.second].key);
    if (!(c.rho > -1 && c.rho < 1)) throw InvalidInput(fmt::format("{}: rho {} is outside (-1, 1)", pair, c.rho));
    const auto i = static_cast<Eigen::Index>(c.first), j = static_cast<Eigen::Index>(c.second);
    if (r(i, j) != 0) throw InvalidInput(fmt::format("{}: given twice", pair));
    r(i, j) = r(j, i) = c.rho;
    correlated_ = correlated_ || c.rho != 0;
  }
  if (correlated_) {
    const Eigen::LLT<Eigen::MatrixXd> llt(r);
    if (llt.info() != Eigen::Success || !(llt.matrixL().toDenseMatrix().diagonal().minCoeff() > 1e-8)) {
      throw InvalidInput("correlation: the correlation matrix is not positive definite, expected a consistent set "
                         "of correlations");
    }
    cholesky_ = llt.matrixL();
  }
}

double InputTransform::value(std::size_t i, double u) const {
  return std::clamp(quantile(inputs_[i].distribution, window_lo_[i] + u * (window_hi_[i] - window_lo_[i])),
                    inputs_[i].lower, inputs_[i].upper);
}

void InputTransform::values(const double* u, double* x) const {
  const std::size_t k = inputs_.size();
  if (!correlated_) {
    for (std::size_t i = 0; i < k; ++i) x[i] = value(i, u[i]);
    return;
  }
  const boost::math::normal_distribution<double> unit(0, 1);
  Eigen::VectorXd z(static_cast<Eigen::Index>(k));
  for (std::size_t i = 0; i < k; ++i) z[static_cast<Eigen::Index>(i)] = boost::math::quantile(unit, u[i]);
  const Eigen::VectorXd correlated = cholesky_.triangularView<Eigen::Lower>() * z;
  for (std::size_t i = 0; i < k; ++i) {
    const double v = boost::math::cdf(unit, correlated[static_cast<Eigen::Index>(i)]);
    x[i] = value(i, std::clamp(v, 0x1p-53, 1 - 0x1p-53));
  }
}

}  // namespace needlekit::uncertainty
