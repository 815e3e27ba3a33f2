#include "needlekit/calibration/parameter_statistics.hpp"

#include <Eigen/SVD>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>

namespace needlekit::calibration {

namespace {

// Directions the singular values say the data do not determine (relative singular value <= the tolerance): their
// parameters are marked not identifiable, with a warning per direction. Returns 1/σ² per singular value (0 for those).
Eigen::VectorXd inverse_squares(const Eigen::VectorXd& sigma, const Eigen::MatrixXd& v,
                                const std::vector<std::string>& names, const ParameterStatisticsOptions& options,
                                ParameterStatistics& s) {
  const double largest = sigma.size() ? sigma(0) : 0;
  Eigen::VectorXd inverse_square = Eigen::VectorXd::Zero(sigma.size());
  for (Eigen::Index k = 0; k < sigma.size(); ++k) {
    if (sigma(k) > options.degeneracy_tolerance * largest) {
      inverse_square(k) = 1 / (sigma(k) * sigma(k));
      continue;
    }
    std::vector<std::string> group;
    for (Eigen::Index j = 0; j < v.rows(); ++j) {
      if (std::abs(v(j, k)) > 0.05 && s.identifiable[j]) {
        s.identifiable[j] = false;
        group.push_back(names[j]);
      }
    }
    if (group.size() >= 2) {
      s.warnings.push_back(fmt::format("degenerate: {} cannot be told apart: the data determine only a combination of "
                                       "them (relative singular value {:.2g}); fix all but one",
                                       fmt::join(group, " and "), largest > 0 ? sigma(k) / largest : 0.0));
    } else if (group.size() == 1) {
      s.warnings.push_back(fmt::format("{}: not determined by the data (relative singular value {:.2g})", group[0],
                                       largest > 0 ? sigma(k) / largest : 0.0));
    }
  }
  return inverse_square;
}

// The correlation matrix of the identifiable parameters from their covariance, warning above the threshold.
void correlations(const Eigen::MatrixXd& covariance, const std::vector<std::string>& names,
                  const ParameterStatisticsOptions& options, ParameterStatistics& s) {
  const Eigen::Index n = covariance.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!s.identifiable[i] || !s.identifiable[j]) continue;
      const double d = std::sqrt(covariance(i, i) * covariance(j, j));
      s.correlation(i, j) = i == j ? 1.0 : (d > 0 ? covariance(i, j) / d : 0.0);
      if (i < j && std::abs(s.correlation(i, j)) > options.correlation_warning) {
        s.warnings.push_back(fmt::format("{} and {} are hardly told apart by the data (correlation {:.4f})", names[i],
                                         names[j], s.correlation(i, j)));
      }
    }
  }
}

}  // namespace

ParameterStatistics parameter_statistics(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                         const std::vector<double>& values, const std::vector<std::string>& names,
                                         const ParameterStatisticsOptions& options) {
  const Eigen::Index m = jacobian.rows(), n = jacobian.cols();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ParameterStatistics s;
  s.degrees_of_freedom = static_cast<int>(m - n);
  s.standard_error.assign(n, nan);
  s.ci95.assign(n, std::nullopt);
  s.identifiable.assign(n, true);
  s.correlation = Eigen::MatrixXd::Constant(n, n, nan);

  // Column scaling: the SVD then compares directions, not units.
  Eigen::VectorXd scale(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    scale(j) = jacobian.col(j).norm();
    if (!(scale(j) > 0)) {
      s.identifiable[j] = false;
      s.warnings.push_back(fmt::format("{}: the residuals do not depend on it at the optimum: no interval", names[j]));
      scale(j) = 1;
    }
  }
  const Eigen::MatrixXd scaled = jacobian * scale.cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinV);
  const Eigen::MatrixXd& v = svd.matrixV();
  const Eigen::VectorXd inverse_square = inverse_squares(svd.singularValues(), v, names, options, s);
  if (m <= n) {
    s.warnings.push_back(fmt::format("{} residuals for {} parameters: no confidence intervals", m, n));
    return s;
  }
  s.residual_variance = residuals.squaredNorm() / static_cast<double>(m - n);
  const Eigen::MatrixXd scaled_covariance = v * inverse_square.asDiagonal() * v.transpose();
  const Eigen::MatrixXd covariance =
      s.residual_variance * scale.cwiseInverse().asDiagonal() * scaled_covariance * scale.cwiseInverse().asDiagonal();
  const boost::math::students_t t_distribution(static_cast<double>(m - n));
  const double t = boost::math::quantile(boost::math::complement(t_distribution, 0.025));
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!s.identifiable[j]) continue;
    s.standard_error[j] = std::sqrt(std::max(covariance(j, j), 0.0));
    s.ci95[j] = std::pair{values[j] - t * s.standard_error[j], values[j] + t * s.standard_error[j]};
    // Identifiable by the singular values, yet the interval is wider than the value: the data hardly pin it down
    // (e.g. a critical pressure above every pressure the needles reach, so that the criterion never fires).
    if (t * s.standard_error[j] > std::abs(values[j])) {
      s.warnings.push_back(fmt::format("{}: hardly determined by the data: its 95 % interval [{:.4g}, {:.4g}] is wider "
                                       "than the value {:.4g} (SI)",
                                       names[j], s.ci95[j]->first, s.ci95[j]->second, values[j]));
    }
  }
  correlations(covariance, names, options, s);
  return s;
}

}  // namespace needlekit::calibration
