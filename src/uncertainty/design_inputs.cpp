#include "needlekit/uncertainty/design_inputs.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "needlekit/core/errors.hpp"

namespace needlekit::uncertainty {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
using units::Dimension;
}  // namespace

const std::vector<DesignInputInfo>& design_inputs() {
  static const std::vector<DesignInputInfo> table{
      {DesignInput::TipDiameter, "needle.tip_diameter", Dimension::Length, "um", 0, kInf,
       "D1 (a cylinder's D1 = D2 change together)"},
      {DesignInput::BaseDiameter, "needle.base_diameter", Dimension::Length, "um", 0, kInf, "D2"},
      {DesignInput::BoreDiameter, "needle.bore_diameter", Dimension::Length, "um", 0, kInf, "D3 (hollow needles)"},
      {DesignInput::Length, "needle.length", Dimension::Length, "um", 0, kInf, "L"},
      {DesignInput::YoungsModulus, "needle.material.youngs_modulus", Dimension::Pressure, "GPa", 0, kInf,
       "E of the needle material"},
      {DesignInput::YieldStrength, "needle.material.yield_strength", Dimension::Pressure, "MPa", 0, kInf,
       "s_y (Johnson column)"},
      {DesignInput::AllowableStress, "needle.material.allowable_stress", Dimension::Pressure, "MPa", 0, kInf,
       "sigma of the critical bending load (Eqs 5.7, 5.8)"},
      {DesignInput::Width, "array.width", Dimension::Length, "um", 0, kInf, "w, the patch width"},
      {DesignInput::Alpha, "tissue.alpha", Dimension::Force, "N", 0, kInf, "alpha of F(d) = alpha e^(tau d) (Eq 4.1)"},
      {DesignInput::Tau, "tissue.tau", Dimension::InverseLength, "/mm", 0, kInf, "tau of Eq 4.1"},
      {DesignInput::SmallTipSlope, "tissue.small_tip_slope", Dimension::InverseLength, "/um", 0, kInf,
       "K of the small-tip line d = K A"},
      {DesignInput::Angle, "insertion.angle", Dimension::Angle, "deg", 0, M_PI / 2,
       "theta from the surface normal, [0, 90) deg"},
      {DesignInput::TargetDepth, "insertion.target_depth", Dimension::Length, "um", 0, kInf, "T"},
  };
  return table;
}

const DesignInputInfo& info(DesignInput input) {
  for (const DesignInputInfo& entry : design_inputs()) {
    if (entry.input == input) return entry;
  }
  return design_inputs().front();
}

DesignInput design_input_from_key(std::string_view key, std::string_view what) {
  std::vector<std::string_view> keys;
  for (const DesignInputInfo& entry : design_inputs()) {
    if (entry.key == key) return entry.input;
    keys.push_back(entry.key);
  }
  throw InvalidInput(fmt::format("{}: '{}' is not an input of the design, expected one of: {}", what, key,
                                 fmt::join(keys, ", ")));
}

DesignValues design_values(const DesignCase& c) {
  DesignValues v;
  v.needle = c.design.needle;
  v.youngs_modulus = c.design.material.youngs_modulus;
  v.yield_strength = c.design.material.yield_strength;
  v.allowable_stress = c.design.material.allowable_stress;
  v.needles_per_row = c.design.needles_per_row;
  v.width = c.design.width;
  v.tissue = c.conditions.tissue;
  v.angle = c.conditions.angle;
  v.target_depth = c.conditions.target_depth;
  return v;
}

double nominal_value(DesignInput input, const DesignValues& v, std::string_view what) {
  const auto missing = [&](std::string_view problem) -> double {
    throw InvalidInput(fmt::format("{}: {}, expected an input the design has", what, problem));
  };
  switch (input) {
    case DesignInput::TipDiameter: return v.needle.tip_diameter;
    case DesignInput::BaseDiameter: return v.needle.base_diameter;
    case DesignInput::BoreDiameter:
      return v.needle.hollow() ? v.needle.bore_diameter : missing("the needle is solid (no bore_diameter)");
    case DesignInput::Length: return v.needle.length;
    case DesignInput::YoungsModulus: return v.youngs_modulus;
    case DesignInput::YieldStrength:
      return v.yield_strength ? *v.yield_strength : missing("the material has no yield_strength");
    case DesignInput::AllowableStress:
      return v.allowable_stress ? *v.allowable_stress : missing("the material has no allowable_stress");
    case DesignInput::Width: return v.width;
    case DesignInput::Alpha: return v.tissue.alpha;
    case DesignInput::Tau: return v.tissue.tau;
    case DesignInput::SmallTipSlope: return v.tissue.small_tip_slope;
    case DesignInput::Angle: return v.angle;
    case DesignInput::TargetDepth: return v.target_depth;
  }
  return 0;
}

void set_value(DesignInput input, double x, DesignValues& v) {
  const bool cylinder = v.needle.shape == needle::Shape::Cylinder;
  switch (input) {
    case DesignInput::TipDiameter:
      v.needle.tip_diameter = x;
      if (cylinder) v.needle.base_diameter = x;
      break;
    case DesignInput::BaseDiameter:
      v.needle.base_diameter = x;
      if (cylinder) v.needle.tip_diameter = x;
      break;
    case DesignInput::BoreDiameter: v.needle.bore_diameter = x; break;
    case DesignInput::Length: v.needle.length = x; break;
    case DesignInput::YoungsModulus: v.youngs_modulus = x; break;
    case DesignInput::YieldStrength: v.yield_strength = x; break;
    case DesignInput::AllowableStress: v.allowable_stress = x; break;
    case DesignInput::Width: v.width = x; break;
    case DesignInput::Alpha: v.tissue.alpha = x; break;
    case DesignInput::Tau: v.tissue.tau = x; break;
    case DesignInput::SmallTipSlope: v.tissue.small_tip_slope = x; break;
    case DesignInput::Angle: v.angle = x; break;
    case DesignInput::TargetDepth: v.target_depth = x; break;
  }
}

}  // namespace needlekit::uncertainty
