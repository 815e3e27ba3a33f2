// Design files (one needle array, for `evaluate` and `sweep`) and design-space files (a grid, for `optimize`), in
// TOML. Every dimensional value is a string with its unit ("70 um", "169 GPa", "6.25 /mm"); a bare number for a
// dimensional quantity, an unknown key, a missing required key and an out-of-range value are errors that name the
// file, the line and the key:  FILE:LINE: key 'needle.tip_diameter': <what is wrong>, expected <what>.
//
// Design file:
//   [needle]     shape (needle::kShapeNames); tip_diameter; base_diameter (a cylinder may omit it: = tip);
//                bore_diameter (omit for a solid needle); length; material = a preset name (materials::
//                material_preset_names()) or an inline table { youngs_modulus, yield_strength?, allowable_stress?,
//                name? }
//   [array]      needles_per_row (integer >= 1); width; spacing_factor (beta of w >= beta*n*D2, >= 0, default 3)
//   [tissue]     model = "skin" | "brain" | { alpha = "0.0183 N", tau = "6.25 /mm", small_tip_slope? = "0.0608 /um",
//                name? }   (optional table; default skin)
//   [insertion]  angle (default "0 deg", [0, 90) deg); target_depth or application = "transdermal" | "aesthetic" |
//                "tattoo" | "brain" (default transdermal, 50 um); buckling_safety_factor, bending_safety_factor
//                (>= 1); end_condition (analysis::kEndConditionNames); effective_length
//                (analysis::kEffectiveLengthNames; uniform columns only); johnson (bool)   (optional table)
//
// Design-space file: top-level shape, hollow (bool, default false), material (as above), tissue (as the model
// above, default "skin"), target_depth (default "50 um"), spacing_factor (default 3), and [ranges] of inclusive
// [min, max, step] arrays: needles_per_row (integers), tip_diameter, base_diameter (a cylinder may omit it),
// bore_diameter (required iff hollow), width, length (strings with units).
#pragma once
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <vector>
#include <string_view>

#include "needlekit/analysis/design_space.hpp"
#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

namespace needlekit::io {

struct DesignFile {
  analysis::ArrayDesign design;
  analysis::InsertionConditions conditions;
  analysis::PerformanceIndexOptions options;
};

// Throws IoError (unreadable file, TOML syntax) or InvalidInput (a missing, unknown or invalid key).
DesignFile read_design_file(const std::filesystem::path& path);
// The same from text; `source_name` stands for the file name in messages.
DesignFile parse_design_toml(std::string_view text, std::string_view source_name);

// The [needle], [tissue] and [insertion] tables of another needlekit file (a patch case file), with the same keys,
// defaults and messages as a design file. `other_tables` lists the file's remaining top-level tables, which the
// caller reads; any other table is an error. design.needles_per_row and design.width keep their defaults.
DesignFile parse_needle_tables(std::string_view text, std::string_view source_name,
                               std::initializer_list<std::string_view> other_tables);

// A design file's tables ([needle], [array], [tissue], [insertion]) in a file that also holds `other_tables` (e.g. an
// uncertainty file's [uncertain] and [sampling]), which the caller reads; any other table is an error.
DesignFile parse_design_tables(std::string_view text, std::string_view source_name,
                               std::initializer_list<std::string_view> other_tables);

// Robust design (uncertainty/robust_design.hpp): a design-space file may add min_success_probability = 0.99 (top
// level) with the [uncertain], [sampling] and [[correlation]] tables of an uncertainty file
// (io/uncertainty_config.hpp). The spread of a design variable (needle.tip_diameter, base_diameter, bore_diameter,
// length, array.width) is centred on every candidate, so it takes no mean or median and must be normal,
// truncated-normal or lognormal; tissue and material inputs are absolute.
struct RobustSpec {
  double min_success_probability = 0.99;
  std::vector<uncertainty::DesignUncertainInput> inputs;
  std::vector<uncertainty::Correlation> correlations;
  uncertainty::PropagationOptions sampling;
};

struct SpaceFile {
  analysis::DesignSpace space;
  std::optional<RobustSpec> robust;  // when min_success_probability is given
};

// Throws IoError (unreadable file, TOML syntax) or InvalidInput (a missing, unknown or invalid key or range).
SpaceFile read_space_file(const std::filesystem::path& path);
SpaceFile parse_space_toml(std::string_view text, std::string_view source_name);

}  // namespace needlekit::io
