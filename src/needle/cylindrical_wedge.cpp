#include "needlekit/needle/cylindrical_wedge.hpp"

#include <algorithm>
#include <cmath>

namespace needlekit::needle {

double cylindrical_wedge_volume(double r, double c, double wedge_length) {
  if (c <= 0 || wedge_length <= 0) return 0.0;
  c = std::min(c, 2 * r);
  const double a = std::sqrt(std::max(0.0, 2 * r * c - c * c));  // half chord, Eq 4.16
  // θ = π/2 + atan((c − r)/a) (Eq 4.16); written with atan2 so that a = 0 (c = 2r) stays finite.
  const double theta = M_PI / 2 + std::atan2(c - r, a);
  return wedge_length / (3 * c) * (a * (3 * r * r - a * a) + 3 * r * r * (c - r) * theta);  // Eq 4.17
}

}  // namespace needlekit::needle
