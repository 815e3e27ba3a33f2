#include "needlekit/uncertainty/sobol_indices.hpp"

#include <cmath>

namespace needlekit::uncertainty {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

double output_variance(const SobolSums& s) {
  if (s.rows < 2) return kNaN;
  const double n = 2.0 * static_cast<double>(s.rows);
  const double mean = (s.sum_a + s.sum_b) / n;
  return std::max(0.0, (s.sum_a2 + s.sum_b2) / n - mean * mean);
}

double first_order_index(const SobolSums& s) {
  const double v = output_variance(s);
  if (!(v > 0)) return kNaN;
  return s.first / static_cast<double>(s.rows) / v;
}

double total_index(const SobolSums& s) {
  const double v = output_variance(s);
  if (!(v > 0)) return kNaN;
  return s.total / (2.0 * static_cast<double>(s.rows)) / v;
}

}  // namespace needlekit::uncertainty
