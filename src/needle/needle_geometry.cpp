#include "needlekit/needle/needle_geometry.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/needle/cylindrical_wedge.hpp"
#include "needlekit/needle/section_properties.hpp"

namespace needlekit::needle {

std::string_view to_string(Shape shape) { return name_of(kShapeNames, shape); }

Shape shape_from_string(std::string_view text, std::string_view what) { return value_of(kShapeNames, text, what); }

void validate(const NeedleGeometry& n, std::string_view where) {
  auto positive = [&](double v, std::string_view key) {
    if (!std::isfinite(v) || v <= 0) {
      throw InvalidInput(fmt::format("{}.{}: {} m is not a positive finite length", where, key, v));
    }
  };
  positive(n.tip_diameter, "tip_diameter");
  positive(n.base_diameter, "base_diameter");
  positive(n.length, "length");
  if (!std::isfinite(n.bore_diameter) || n.bore_diameter < 0) {
    throw InvalidInput(fmt::format("{}.bore_diameter: {} m must be a finite length >= 0 (omit it for a solid needle)",
                                   where, n.bore_diameter));
  }
  if (n.tip_diameter > n.base_diameter * (1 + 1e-12)) {
    throw InvalidInput(fmt::format("{}.tip_diameter: {:.6g} um is larger than base_diameter {:.6g} um (D1 <= D2)",
                                   where, n.tip_diameter * 1e6, n.base_diameter * 1e6));
  }
  if (n.shape == Shape::Cylinder && std::abs(n.tip_diameter - n.base_diameter) > 1e-12 * n.base_diameter) {
    throw InvalidInput(fmt::format("{}: a cylinder needs tip_diameter == base_diameter (got {:.6g} um and {:.6g} um)",
                                   where, n.tip_diameter * 1e6, n.base_diameter * 1e6));
  }
  if (n.hollow() && (n.bore_diameter >= n.tip_diameter || n.bore_diameter >= n.base_diameter)) {
    throw InvalidInput(fmt::format("{}.bore_diameter: {:.6g} um must be smaller than the tip ({:.6g} um) and the "
                                   "base ({:.6g} um) diameters",
                                   where, n.bore_diameter * 1e6, n.tip_diameter * 1e6, n.base_diameter * 1e6));
  }
}

double tip_area(const NeedleGeometry& n) {
  if (n.shape != Shape::Bevel) return M_PI / 4 * n.tip_diameter * n.tip_diameter;
  // Circular segment of sagitta D1 in the circle of radius r = D2/2 (notes, "Tip area"):
  // A = r²·acos((r − D1)/r) − (r − D1)·√(2rD1 − D1²).
  const double r = n.base_diameter / 2, h = n.tip_diameter;
  return r * r * std::acos((r - h) / r) - (r - h) * std::sqrt(std::max(0.0, 2 * r * h - h * h));
}

double outer_diameter_at(const NeedleGeometry& n, double s) {
  if (n.shape == Shape::Cone) return n.tip_diameter + (n.base_diameter - n.tip_diameter) * s / n.length;
  return n.base_diameter;
}

double volume(const NeedleGeometry& n) {
  const double bore = M_PI / 4 * n.bore_diameter * n.bore_diameter * n.length;
  switch (n.shape) {
    case Shape::Cylinder: return M_PI / 4 * n.base_diameter * n.base_diameter * n.length - bore;
    case Shape::Cone: {
      const double d1 = n.tip_diameter, d2 = n.base_diameter;
      return M_PI / 12 * n.length * (d1 * d1 + d1 * d2 + d2 * d2) - bore;  // frustum (Table 4.2 with h = L)
    }
    case Shape::Bevel: {
      if (!n.hollow()) {
        // Full cylinder minus the large wedge (Eq 4.18 = Eq 4.17 with c = D2 − D1, ℓ = L).
        const double r = n.base_diameter / 2;
        return M_PI * r * r * n.length - cylindrical_wedge_volume(r, n.base_diameter - n.tip_diameter, n.length);
      }
      // Hollow bevel: the bore is partly cut by the bevel plane; integrate the section area (composite Simpson;
      // the integrand is smooth except where the plane leaves the bore, so use many intervals).
      constexpr int kIntervals = 4000;
      const double ds = n.length / kIntervals;
      double sum = 0;
      for (int i = 0; i <= kIntervals; ++i) {
        const double w = (i == 0 || i == kIntervals) ? 1 : (i % 2 ? 4 : 2);
        sum += w * section_at(n, i * ds).area;
      }
      return sum * ds / 3;
    }
  }
  return 0;
}

}  // namespace needlekit::needle
