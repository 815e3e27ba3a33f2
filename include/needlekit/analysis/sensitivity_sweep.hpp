// One-at-a-time sensitivity of the performance index (dissertation §6.3.1, Figs 6.18 and 6.19): one parameter of
// an array design is varied over an inclusive range while every other input stays fixed.
#pragma once
#include <string_view>
#include <vector>

#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/units.hpp"

namespace needlekit::analysis {

enum class SweepParameter { TipDiameter, BaseDiameter, BoreDiameter, Length, Width, NeedlesPerRow, Angle, TargetDepth };
inline constexpr EnumTable<SweepParameter, 8> kSweepParameterNames{{
    {SweepParameter::TipDiameter, "tip_diameter", "D1 (length)"},
    {SweepParameter::BaseDiameter, "base_diameter", "D2 (length)"},
    {SweepParameter::BoreDiameter, "bore_diameter", "D3 (length)"},
    {SweepParameter::Length, "length", "L (length)"},
    {SweepParameter::Width, "width", "w, the array's width (length)"},
    {SweepParameter::NeedlesPerRow, "needles_per_row", "n (a count)"},
    {SweepParameter::Angle, "angle", "insertion angle (angle)"},
    {SweepParameter::TargetDepth, "target_depth", "T (length)"},
}};

std::string_view to_string(SweepParameter parameter);
// The inverse of to_string; throws InvalidInput naming `what` and listing the names otherwise.
SweepParameter sweep_parameter_from_string(std::string_view text, std::string_view what = "--vary");
// Length for the diameters, the length, the width and the target depth; Angle; Dimensionless for needles_per_row.
units::Dimension sweep_parameter_dimension(SweepParameter parameter);

struct SweepOptions {
  SweepParameter parameter = SweepParameter::BaseDiameter;
  double from = 0;  // SI (m, rad, or a count), finite
  double to = 0;    // SI, >= from; the values are from, from + step, ..., <= to (relative tolerance 1e-9·step),
                   // rounded to 12 significant digits
  double step = 0;  // SI, > 0; whole numbers for needles_per_row; at most 1e6 values
};

struct SweepPoint {
  double value = 0;                // SI value of the varied parameter
  ArrayDesign design;              // the design evaluated at this point
  InsertionConditions conditions;  // the conditions evaluated at this point
  PerformanceIndexResult result;   // ConstraintViolated, with the validation message as reason, when the varied
                                   // value makes the design invalid (e.g. D1 > D2 for a cone)
};

struct SweepResult {
  SweepParameter parameter = SweepParameter::BaseDiameter;
  std::vector<SweepPoint> points;  // in increasing value
};

// Varying a cylinder's tip or base diameter changes both (D1 = D2). Throws InvalidInput (naming "--vary") for an
// empty range, step <= 0, non-finite bounds or too many values, and for an invalid base design.
SweepResult sensitivity_sweep(const ArrayDesign& design, const InsertionConditions& conditions,
                              const PerformanceIndexOptions& options, const SweepOptions& sweep);

}  // namespace needlekit::analysis
