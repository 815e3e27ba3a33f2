#include "needlekit/analysis/bending.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/needle/section_properties.hpp"

namespace needlekit::analysis {

double critical_bending_load(const needle::NeedleGeometry& n, double sigma) {
  needle::validate(n);
  if (!(sigma > 0) || !std::isfinite(sigma)) {
    throw InvalidInput(fmt::format("allowable_stress: {} Pa must be positive", sigma));
  }
  const double l = n.length;
  if (!n.hollow() && n.shape == needle::Shape::Cylinder) {
    return sigma * M_PI * std::pow(n.tip_diameter, 3) / (32 * l);  // Eq 5.7
  }
  if (!n.hollow() && n.shape == needle::Shape::Cone) {
    const double t = n.base_diameter / n.tip_diameter;
    if (t >= 1.5) return 27 * sigma * (t - 1) * M_PI * std::pow(n.tip_diameter, 3) / (128 * l);  // Eq 5.8
    return sigma * M_PI * std::pow(n.base_diameter, 3) / (32 * l);  // maximum stress at the base (notes)
  }
  // Hollow and bevel sections: P_Be = σ·min_s S(s)/s — a scan, then golden-section refinement of the bracket.
  auto ratio = [&](double s) { return needle::section_at(n, s).section_modulus_min / s; };
  constexpr int kScan = 200;
  int best = kScan;
  double best_value = ratio(l);
  for (int i = 1; i < kScan; ++i) {
    const double v = ratio(l * i / kScan);
    if (v < best_value) best_value = v, best = i;
  }
  if (best < kScan) {
    double a = l * (best - 1) / kScan, b = l * (best + 1) / kScan;
    const double phi = (std::sqrt(5.0) - 1) / 2;
    double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
    double f1 = ratio(x1), f2 = ratio(x2);
    for (int it = 0; it < 60 && b - a > 1e-12 * l; ++it) {
      if (f1 < f2) {
        b = x2, x2 = x1, f2 = f1, x1 = b - phi * (b - a), f1 = ratio(x1);
      } else {
        a = x1, x1 = x2, f1 = f2, x2 = a + phi * (b - a), f2 = ratio(x2);
      }
    }
    best_value = std::min({best_value, f1, f2});
  }
  return sigma * best_value;
}

double angled_buckling_force(double puncture_force, double angle) {
  if (!(angle >= 0 && angle < M_PI / 2)) {
    throw InvalidInput(fmt::format("angle: {:.6g} deg must be in [0, 90) deg", angle * 180 / M_PI));
  }
  return std::abs(puncture_force) / std::cos(angle);  // Eq 5.3
}

double angled_bending_force(double puncture_force, double angle) {
  if (!(angle >= 0 && angle < M_PI / 2)) {
    throw InvalidInput(fmt::format("angle: {:.6g} deg must be in [0, 90) deg", angle * 180 / M_PI));
  }
  return std::abs(puncture_force) * std::tan(angle);  // Eq 5.4
}

}  // namespace needlekit::analysis
