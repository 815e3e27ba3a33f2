// Needle materials (dissertation §2.4.2, §6.3, §6.4) with the source of every value.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace needlekit::materials {

struct NeedleMaterial {
  std::string name;
  double youngs_modulus = 0;               // Pa, E > 0
  std::optional<double> yield_strength;    // Pa, s_y (fracture strength for brittle silicon); Johnson column, C_c
  std::optional<double> allowable_stress;  // Pa, σ of Eqs 5.7/5.8 (critical bending load)
  std::string source;                      // where each value comes from
};

// The preset names, in a stable order: silicon, su-8, plga, pla, pga, titanium, stainless-steel, e-shell-200,
// e-shell-300.
std::vector<std::string> material_preset_names();

// A preset by name (case-insensitive, "SU-8" == "su8" == "su-8"); throws InvalidInput naming `what` and listing the
// presets if unknown.
NeedleMaterial material_preset(std::string_view name, std::string_view what = "material");

// Throws InvalidInput naming the field (prefixed by `where`) for non-positive or non-finite properties.
void validate(const NeedleMaterial& material, std::string_view where = "material");

}  // namespace needlekit::materials
