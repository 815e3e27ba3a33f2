// The inputs an options struct was run with, as JSON, from its parameter table (core/parameter.hpp) alone: one key per
// row under the case file's table the row is written in ({"loading": {"depth_m": 0.0002, ...}}; a row in no table at
// the top). A quantity's key names its SI unit ("depth_m", "critical_pressure_Pa"), a pure number or an integer is
// written as is, an optional quantity not given as null, a flag as the file writes it (a negated row's file key and value), a choice by its name. What
// `needlekit indent --json` echoes under "inputs"; a new row appears there with nothing else to write.
#pragma once
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <string_view>

#include "needlekit/core/parameter.hpp"

namespace needlekit::io {

namespace detail {

// The SI unit as a key suffix: "m" -> "_m", "m^2" -> "_m2", "1/m" -> "_per_m", "N/m" -> "_N_per_m".
inline std::string unit_suffix(units::Dimension dimension) {
  std::string suffix;
  for (const char c : units::si_symbol(dimension)) {
    if (c == '^') continue;
    if (c == '/') {
      suffix += "_per_";
    } else {
      suffix += c;
    }
  }
  if (suffix.starts_with("1_per_")) suffix.erase(0, 1);  // "1/m": "_per_m"
  return suffix.empty() || suffix.starts_with("_") ? suffix : "_" + suffix;
}

// The object a row's key goes in: its table's, or the top.
inline nlohmann::json& table_of(std::string_view group, nlohmann::json& json) {
  return group.empty() ? json : json[std::string(group)];
}

template <class Options, class Value>
void add_row_json(const Parameter<Options, Value>& row, const Options& options, nlohmann::json& json) {
  table_of(row.group, json)[std::string(row.key) + unit_suffix(row.dimension)] = options.*row.field;
}
template <class Options>
void add_row_json(const OptionalQuantity<Options>& row, const Options& options, nlohmann::json& json) {
  const std::optional<double>& value = options.*row.field;
  nlohmann::json& slot = table_of(row.group, json)[std::string(row.key) + unit_suffix(row.dimension)];
  slot = value ? nlohmann::json(*value) : nlohmann::json(nullptr);  // null: not given
}
template <class Options>
void add_row_json(const Flag<Options>& row, const Options& options, nlohmann::json& json) {
  table_of(row.group, json)[std::string(row.key)] = row.negated ? !(options.*row.field) : options.*row.field;
}
template <class Options, class Value, std::size_t N>
void add_row_json(const Choice<Options, Value, N>& row, const Options& options, nlohmann::json& json) {
  table_of(row.group, json)[std::string(row.key)] = name_of(*row.names, options.*row.field);
}

}  // namespace detail

// Adds the rows of `table` with the values of `options` to `json` (an object).
template <class Options, class Table>
void add_parameters_json(const Table& table, const Options& options, nlohmann::json& json) {
  for_each_parameter(table, [&](const auto& row) { detail::add_row_json(row, options, json); });
}

}  // namespace needlekit::io
