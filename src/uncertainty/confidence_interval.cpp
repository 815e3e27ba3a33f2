#include "needlekit/uncertainty/confidence_interval.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <cmath>

namespace needlekit::uncertainty {

Interval wilson_interval(std::size_t successes, std::size_t trials) {
  if (trials == 0) return {0, 1};
  constexpr double z = 1.959963984540054;
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double denominator = 1 + z * z / n;
  const double center = (p + z * z / (2 * n)) / denominator;
  const double half = z * std::sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denominator;
  return {std::max(0.0, center - half), std::min(1.0, center + half)};
}

Interval replicate_interval(double center, const std::vector<double>& replicates) {
  const std::size_t g = replicates.size();
  if (g < 2) return {center, center};
  double mean = 0;
  for (double r : replicates) mean += r;
  mean /= static_cast<double>(g);
  double sum_squares = 0;
  for (double r : replicates) sum_squares += (r - mean) * (r - mean);
  const double sd = std::sqrt(sum_squares / static_cast<double>(g - 1));
  const double t = boost::math::quantile(boost::math::students_t_distribution<double>(static_cast<double>(g - 1)), 0.975);
  const double half = t * sd / std::sqrt(static_cast<double>(g));
  return {center - half, center + half};
}

}  // namespace needlekit::uncertainty
