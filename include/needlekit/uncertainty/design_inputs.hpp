// The inputs of a design file that may be uncertain, declared once: the key as written in a design file, its
// dimension, the unit results show it in, its physical range and its meaning. The UQ-file reader, the CLI help,
// the JSON writer and docs/uncertainty.md all use this table.
#pragma once
#include <string_view>
#include <vector>

#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/core/units.hpp"

namespace needlekit::uncertainty {

// One needle array with its insertion conditions and evaluation options (the contents of a design file).
struct DesignCase {
  analysis::ArrayDesign design;
  analysis::InsertionConditions conditions;
  analysis::PerformanceIndexOptions options;
};

enum class DesignInput {
  TipDiameter, BaseDiameter, BoreDiameter, Length, YoungsModulus, YieldStrength, AllowableStress, Width,
  Alpha, Tau, SmallTipSlope, Angle, TargetDepth,
};

struct DesignInputInfo {
  DesignInput input;
  std::string_view key;        // as in a design file: "needle.tip_diameter", "tissue.alpha", ...
  units::Dimension dimension;
  std::string_view unit;       // for messages and reports ("um", "GPa", "N", "/mm", "deg")
  double lower, upper;         // physical range (SI); samples outside it are truncated or refused
  std::string_view meaning;
};

const std::vector<DesignInputInfo>& design_inputs();
const DesignInputInfo& info(DesignInput input);
// Throws InvalidInput naming `what` and listing the keys for an unknown key.
DesignInput design_input_from_key(std::string_view key, std::string_view what);

// The numeric inputs of a design that a sample may change (copied per sample: no heap strings but the tissue's
// short name).
struct DesignValues {
  needle::NeedleGeometry needle;
  double youngs_modulus = 0;
  std::optional<double> yield_strength, allowable_stress;
  int needles_per_row = 1;
  double width = 0;
  analysis::PunctureModel tissue;
  double angle = 0;
  double target_depth = 0;
};
DesignValues design_values(const DesignCase& design_case);

// The nominal value of an input in a design. Throws InvalidInput naming `what` when the design has no such value
// (a bore on a solid needle, an allowable stress or yield strength the material does not have).
double nominal_value(DesignInput input, const DesignValues& values, std::string_view what);
// Sets an input (a cylinder's tip and base diameter together).
void set_value(DesignInput input, double value, DesignValues& values);

// Mass of a distribution that may fall outside an input's physical range before the input is refused: below it
// the distribution is truncated to the range (and the result says by how much), above it the input is an error
// that names the key and suggests truncated-normal.
inline constexpr double kMaxTruncatedMass = 1e-3;

}  // namespace needlekit::uncertainty
