#include "needlekit/analysis/skin_permeation.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/needle/cylindrical_wedge.hpp"

namespace needlekit::analysis {

using needle::NeedleGeometry;
using needle::Shape;

double diameter_at_skin_surface(const NeedleGeometry& n, double h) {
  if (n.shape == Shape::Cone) return n.tip_diameter + (n.base_diameter - n.tip_diameter) * h / n.length;
  return n.base_diameter;
}

double embedded_volume(const NeedleGeometry& n, double h) {
  h = std::clamp(h, 0.0, n.length);
  switch (n.shape) {
    case Shape::Cylinder: return M_PI / 4 * h * n.tip_diameter * n.tip_diameter;  // Table 4.2
    case Shape::Cone: {
      const double d1 = n.tip_diameter, b = diameter_at_skin_surface(n, h);
      return M_PI / 12 * h * (d1 * d1 + d1 * b + b * b);  // Table 4.2
    }
    case Shape::Bevel: {
      const double r = n.base_diameter / 2, c = n.base_diameter - n.tip_diameter;
      const double large_wedge = needle::cylindrical_wedge_volume(r, c, n.length);  // Eq 4.18
      const double x = c / n.length * (n.length - h);                                // §4.5: x = (D2−D1)(L−h)/L
      const double small_wedge = needle::cylindrical_wedge_volume(r, x, n.length - h);  // Eq 4.19
      return M_PI / 4 * h * n.base_diameter * n.base_diameter - (large_wedge - small_wedge);  // Table 4.2
    }
  }
  return 0;
}

double permeation_factor(const NeedleGeometry& n, double h) {
  if (h <= 0) return 0;
  return embedded_volume(n, h) / h;  // Table 4.4
}

double hole_volume(const NeedleGeometry& n, double h, double delta) {
  return std::pow(1 + delta, 3) * embedded_volume(n, h);  // Eqs 4.20–4.22
}

double gap_volume(const NeedleGeometry& n, double h, double delta) {
  return hole_volume(n, h, delta) - embedded_volume(n, h);
}

double fractional_skin_volume(const NeedleGeometry& n, double h, double delta, double pitch) {
  const double gap_factor = (delta * delta * delta + 3 * delta * delta + 3 * delta) / (1 + delta);
  return gap_factor * permeation_factor(n, h) / (pitch * pitch);  // Table 4.3
}

double ideal_permeation_depth(bool hollow, double length, double deformation, double target_depth) {
  if (length < deformation + target_depth) return 0;  // Eq 4.23, "otherwise"
  return hollow ? length - deformation : target_depth;
}

double application_target_depth(std::string_view application, std::string_view what) {
  if (application == "transdermal") return 50e-6;
  if (application == "aesthetic" || application == "tattoo") return 1.5e-3;
  if (application == "brain") return 1e-3;
  throw InvalidInput(fmt::format("{}: unknown application '{}', expected transdermal, aesthetic, tattoo or brain "
                                 "(or give insertion.target_depth with a unit)",
                                 what, application));
}

}  // namespace needlekit::analysis
