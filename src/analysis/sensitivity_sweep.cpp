#include "needlekit/analysis/sensitivity_sweep.hpp"

#include <array>
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <utility>

#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {
namespace {

constexpr double kMaxPoints = 1e6;

// The values from, from + step, ..., <= to, with the checks of SweepOptions.
std::vector<double> sweep_values(const SweepOptions& sweep) {
  const std::string_view name = to_string(sweep.parameter);
  if (!std::isfinite(sweep.from) || !std::isfinite(sweep.to) || !std::isfinite(sweep.step)) {
    throw InvalidInput(fmt::format("--vary {}: from, to and step must be finite numbers", name));
  }
  if (!(sweep.step > 0)) {
    throw InvalidInput(fmt::format("--vary {}: step {} must be > 0", name, sweep.step));
  }
  if (sweep.to < sweep.from) {
    throw InvalidInput(fmt::format("--vary {}: empty range, to {} < from {} (SI units), expected from <= to", name,
                                   sweep.to, sweep.from));
  }
  const double count = std::floor((sweep.to - sweep.from) / sweep.step + 1e-9) + 1;
  if (count > kMaxPoints) {
    throw InvalidInput(fmt::format("--vary {}: {:.3g} values, expected at most {:.0g} (use a larger step)", name,
                                   count, kMaxPoints));
  }
  if (sweep.parameter == SweepParameter::NeedlesPerRow &&
      (sweep.from != std::round(sweep.from) || sweep.step != std::round(sweep.step))) {
    throw InvalidInput(fmt::format("--vary needles_per_row: from {} and step {} must be whole numbers", sweep.from,
                                   sweep.step));
  }
  std::vector<double> values(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < values.size(); ++i) {
    // 12 digits: 100 um + 1·50 um is then the same double as a base diameter given as "150 um", not 1 ulp above it.
    values[i] = units::round_to_12_digits(sweep.from + static_cast<double>(i) * sweep.step);
  }
  return values;
}

// The design and conditions with the parameter set to `value`.
void apply(SweepParameter parameter, double value, ArrayDesign& design, InsertionConditions& conditions) {
  needle::NeedleGeometry& needle = design.needle;
  const bool cylinder = needle.shape == needle::Shape::Cylinder;
  switch (parameter) {
    case SweepParameter::TipDiameter:
      needle.tip_diameter = value;
      if (cylinder) needle.base_diameter = value;
      break;
    case SweepParameter::BaseDiameter:
      needle.base_diameter = value;
      if (cylinder) needle.tip_diameter = value;
      break;
    case SweepParameter::BoreDiameter: needle.bore_diameter = value; break;
    case SweepParameter::Length: needle.length = value; break;
    case SweepParameter::Width: design.width = value; break;
    case SweepParameter::NeedlesPerRow: design.needles_per_row = static_cast<int>(std::lround(value)); break;
    case SweepParameter::Angle: conditions.angle = value; break;
    case SweepParameter::TargetDepth: conditions.target_depth = value; break;
  }
}

}  // namespace

std::string_view to_string(SweepParameter parameter) { return name_of(kSweepParameterNames, parameter); }

SweepParameter sweep_parameter_from_string(std::string_view text, std::string_view what) {
  return value_of(kSweepParameterNames, text, what);
}

units::Dimension sweep_parameter_dimension(SweepParameter parameter) {
  switch (parameter) {
    case SweepParameter::NeedlesPerRow: return units::Dimension::Dimensionless;
    case SweepParameter::Angle: return units::Dimension::Angle;
    default: return units::Dimension::Length;
  }
}

SweepResult sensitivity_sweep(const ArrayDesign& design, const InsertionConditions& conditions,
                              const PerformanceIndexOptions& options, const SweepOptions& sweep) {
  const std::vector<double> values = sweep_values(sweep);
  performance_index(design, conditions, options);  // an invalid base design is an error, not a sweep outcome

  SweepResult result;
  result.parameter = sweep.parameter;
  result.points.reserve(values.size());
  for (const double value : values) {
    SweepPoint point;
    point.value = value;
    point.design = design;
    point.conditions = conditions;
    apply(sweep.parameter, value, point.design, point.conditions);
    try {
      point.result = performance_index(point.design, point.conditions, options);
    } catch (const InvalidInput& error) {
      point.result.status = PerformanceStatus::ConstraintViolated;
      point.result.reason = error.what();
    }
    result.points.push_back(std::move(point));
  }
  return result;
}

}  // namespace needlekit::analysis
