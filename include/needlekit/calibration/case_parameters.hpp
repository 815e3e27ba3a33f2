// The quantities a calibration may fit, addressed by their TOML paths in the experiments' case files
// ("tissue.layers.0.youngs_modulus", "puncture.critical_pressure"), and reading and replacing one value in a case
// file's text. The text is edited in place (comments, layout and line numbers stay), so a calibrated case reads back
// with the same readers and messages.
#pragma once
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "needlekit/core/units.hpp"

namespace needlekit::calibration {

// One kind of calibratable key: a path pattern ('N' stands for a layer or table index), the case kinds it lives in
// and what it means. The one table: the calibration reader, its messages and `calibrate --help` read it.
struct ParameterKind {
  std::string_view pattern;
  std::string_view meaning;
};
std::span<const ParameterKind> parameter_kinds();
// The kind of `path`, or empty when the path is not calibratable (geometry, mesh and solver keys are not: they
// change the mesh the calibration runs on).
const ParameterKind* parameter_kind_of(std::string_view path);
// "tissue.layers.N.youngs_modulus, ..." for messages.
std::string parameter_kind_list();

// A value found in a case file.
struct CaseValue {
  units::Dimension dimension = units::Dimension::Dimensionless;  // a bare number: Dimensionless
  double value = 0;  // SI
  int line = 0;      // 1-based line of the value in the case text
};

// The value at the dotted path ("a.b.0.c" = TOML's a.b[0].c) of the case text, or empty when the path does not exist
// or does not hold a number or a quantity with a unit. Throws IoError for TOML syntax errors (naming `source_name`).
std::optional<CaseValue> case_value(std::string_view case_text, std::string_view path, std::string_view source_name);

// The case text with the value at `path` (which must exist) replaced by `value` (SI), written as a quantity in
// `unit` (default the SI unit of `dimension`) with `significant_digits` digits, or as a bare number for
// Dimensionless values.
std::string with_case_value(std::string_view case_text, std::string_view path, double value, units::Dimension dimension,
                            std::string_view unit = {}, int significant_digits = 17);

// The unit symbol of a quantity's text ("0.2 MPa" -> "MPa"; "" for a bare number).
std::string unit_of(std::string_view quantity_text);

}  // namespace needlekit::calibration
