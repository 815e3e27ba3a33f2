#include "needlekit/core/plausible_scale.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

namespace needlekit::units {

std::string readable_length(double length) {
  const double size = std::abs(length);
  if (size >= 1) return fmt::format("{:.4g} m", length);
  if (size >= 1e-3) return fmt::format("{:.4g} mm", length * 1e3);
  if (size >= 1e-6) return fmt::format("{:.4g} um", length * 1e6);
  return fmt::format("{:.4g} nm", length * 1e9);
}

std::optional<std::string> implausible_length(std::string_view what, double length, double low, double high) {
  if (!(length > 0) || (length >= low && length <= high)) return std::nullopt;
  // The unit slips in the order of likelihood: one prefix step (1000), then cm <-> mm or m (10, 100).
  std::vector<std::string> fixes;
  for (const double factor : {1e3, 1e2, 1e1, 1e6}) {
    const double fixed = length > high ? length / factor : length * factor;
    if (fixed >= low && fixed <= high) {
      fixes.push_back(fmt::format("with the unit {:g}x {} it would be {}", factor, length > high ? "smaller" : "larger",
                                  readable_length(fixed)));
    }
  }
  std::string text = fmt::format("{} is {}, outside the plausible {} to {}", what, readable_length(length),
                                 readable_length(low), readable_length(high));
  if (!fixes.empty()) text += ": a unit mistake? " + fixes.front();
  return text;
}

}  // namespace needlekit::units
