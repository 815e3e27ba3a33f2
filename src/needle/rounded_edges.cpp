#include "needlekit/needle/rounded_edges.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "needlekit/core/errors.hpp"

namespace needlekit::needle {

double max_edge_radius(const NeedleGeometry& needle) {
  const double tip = needle.tip_diameter / 2;
  return needle.hollow() ? std::min(tip, (needle.tip_diameter - needle.bore_diameter) / 4) : tip;
}

double default_edge_radius(const NeedleGeometry& needle) {
  return std::min(kTypicalEdgeRadius, max_edge_radius(needle) / 2);
}

ErodedNeedle eroded_needle(const NeedleGeometry& needle, double radius, std::string_view where) {
  validate(needle, where);
  const double limit = max_edge_radius(needle);
  if (!std::isfinite(radius) || radius < 0 || radius >= limit) {
    throw InvalidInput(fmt::format("{}.edge_radius: {:.6g} um, expected at least 0 and less than {:.6g} um ({})",
                                   where, radius * 1e6, limit * 1e6,
                                   needle.hollow() ? "the tip's radius or a quarter of its wall, (D1 - D3) / 4"
                                   : needle.shape == Shape::Bevel ? "half the tip face's sagitta D1"
                                                                  : "the tip's radius"));
  }
  ErodedNeedle eroded{needle, 0.0};
  if (radius == 0) return eroded;
  NeedleGeometry& core = eroded.core;
  const double r2 = needle.base_diameter / 2, length = needle.length;
  if (needle.hollow()) core.bore_diameter = needle.bore_diameter + 2 * radius;
  switch (needle.shape) {
    case Shape::Cylinder:
      core.tip_diameter = core.base_diameter = needle.base_diameter - 2 * radius;
      core.length = length - radius;
      break;
    case Shape::Cone: {
      const double k = (needle.base_diameter - needle.tip_diameter) / (2 * length);  // dr/ds, s from the tip
      const double inward = radius * std::sqrt(1 + k * k);                          // radial shift of the wall
      core.length = length - radius;
      core.base_diameter = 2 * (r2 - inward);
      core.tip_diameter = 2 * (needle.tip_diameter / 2 + k * radius - inward);
      break;
    }
    case Shape::Bevel: {
      // The cut plane x = r - k z (z from the base, k = (D2 - D1) / L) moved in along its normal: x = r - k z - ρ√(1+k²);
      // it meets the core's circle x = r - ρ at z_b = ρ (1 - √(1+k²)) / k <= 0.
      const double k = (needle.base_diameter - needle.tip_diameter) / length;
      const double root = std::sqrt(1 + k * k);
      eroded.base_offset = k > 0 ? radius * (1 - root) / k : 0.0;
      const double tip_z = length - radius;
      core.base_diameter = 2 * (r2 - radius);
      core.length = tip_z - eroded.base_offset;
      core.tip_diameter = core.base_diameter - k * core.length;  // the sagitta left at the lowered tip
      break;
    }
  }
  validate(core, fmt::format("{} eroded by edge_radius", where));
  return eroded;
}

}  // namespace needlekit::needle
