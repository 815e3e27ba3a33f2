#include "needlekit/analysis/design_space.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {

std::uint64_t grid_count(const GridRange& r, std::string_view key) {
  if (!std::isfinite(r.min) || !std::isfinite(r.max) || !std::isfinite(r.step)) {
    throw InvalidInput(fmt::format("ranges.{}: min, max and step must be finite", key));
  }
  if (r.step <= 0) throw InvalidInput(fmt::format("ranges.{}: step {} must be > 0", key, r.step));
  if (r.max < r.min) {
    throw InvalidInput(fmt::format("ranges.{}: empty range (max {} < min {})", key, r.max, r.min));
  }
  const double count = std::floor((r.max - r.min) / r.step + 1e-9) + 1;
  if (count > 1e15) throw InvalidInput(fmt::format("ranges.{}: {:.3g} values is too many", key, count));
  return static_cast<std::uint64_t>(count);
}

std::vector<double> grid_values(const GridRange& r, std::string_view key) {
  const std::uint64_t count = grid_count(r, key);
  std::vector<double> values(count);
  for (std::uint64_t i = 0; i < count; ++i) values[i] = r.min + static_cast<double>(i) * r.step;
  return values;
}

DesignSpace figure_6_20_space(needle::Shape shape, bool hollow) {
  DesignSpace s;
  s.shape = shape;
  s.hollow = hollow;
  s.material = materials::material_preset("silicon");
  return s;  // the defaults of DesignSpace are the Fig 6.20 ranges
}

std::uint64_t design_space_size(const DesignSpace& s) {
  const std::uint64_t n = grid_count(s.needles_per_row, "needles_per_row");
  const std::uint64_t d1 = grid_count(s.tip_diameter, "tip_diameter");
  const std::uint64_t d2 = s.shape == needle::Shape::Cylinder ? 1 : grid_count(s.base_diameter, "base_diameter");
  const std::uint64_t d3 = s.hollow ? grid_count(s.bore_diameter, "bore_diameter") : 1;
  const std::uint64_t w = grid_count(s.width, "width");
  const std::uint64_t l = grid_count(s.length, "length");
  const long double total = static_cast<long double>(n) * d1 * d2 * d3 * w * l;
  if (total > 1.8e19L) throw InvalidInput("the design space has more than 1.8e19 points");
  return n * d1 * d2 * d3 * w * l;
}

}  // namespace needlekit::analysis
