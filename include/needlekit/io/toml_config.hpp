// The io folder's toolkit for reading TOML case files, with errors that name FILE:LINE, the dotted key, the value
// and what was expected: every case reader of io uses it, and so does the calibration file reader, which sits above
// io (docs/architecture.md). It exposes toml++, a private dependency of the library, so it is not installed
// (CMakeLists.txt excludes it): programs built on an installed needlekit read case files through the readers.
#pragma once
#include <toml++/toml.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "needlekit/analysis/puncture_model.hpp"
#include "needlekit/analysis/skin_permeation.hpp"
#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/limits.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::io::config {

using units::Dimension;

static_assert(TOML_EXCEPTIONS, "the config reader relies on toml::parse throwing toml::parse_error");

// "FILE:LINE:" of a node (line 1 when toml++ knows no position, e.g. for the root table).
inline std::string location(std::string_view file, const toml::source_region& region) {
  return fmt::format("{}:{}:", file, region.begin.line == 0 ? 1u : region.begin.line);
}

inline std::string_view example_of(Dimension dimension) {
  switch (dimension) {
    case Dimension::Length: return "\"70 um\"";
    case Dimension::Pressure: return "\"169 GPa\"";
    case Dimension::Force: return "\"0.0183 N\"";
    case Dimension::InverseLength: return "\"6.25 /mm\"";
    case Dimension::Angle: return "\"10 deg\"";
    case Dimension::Stiffness: return "\"1 N/mm\"";
    case Dimension::Energy: return "\"0.05 mJ\"";
    default: return "\"1\"";
  }
}

inline std::string expected_quantity(Dimension dimension) {
  return fmt::format("a {} with its unit, e.g. {}", units::dimension_name(dimension), example_of(dimension));
}

// What a node is, for "... is <this>, expected ..." messages.
inline std::string describe(const toml::node& node) {
  if (node.is_string()) return fmt::format("the string \"{}\"", node.as_string()->get());
  if (node.is_integer()) return std::to_string(node.as_integer()->get());
  if (node.is_floating_point()) return fmt::format("{}", node.as_floating_point()->get());
  if (node.is_boolean()) return node.as_boolean()->get() ? "true" : "false";
  if (node.is_table()) return "a table";
  if (node.is_array()) return "an array";
  return "a date or time";
}

// One TOML table of the file, under its dotted key path. Unknown keys are rejected on construction, so a typo is
// reported as such rather than as a missing key.
class Section {
public:
  Section(const toml::table& table, std::string path, std::string_view file,
          std::initializer_list<std::string_view> allowed_keys)
      : Section(table, std::move(path), file, std::vector<std::string_view>(allowed_keys)) {}
  Section(const toml::table& table, std::string path, std::string_view file,
          const std::vector<std::string_view>& allowed_keys)
      : table_(table), path_(std::move(path)), file_(file) {
    for (auto&& [key, node] : table_) {
      bool known = false;
      for (std::string_view allowed : allowed_keys) known = known || key.str() == allowed;
      if (!known) {
        throw InvalidInput(fmt::format("{} unknown key '{}', expected one of: {}", location(file_, key.source()),
                                       key_path(key.str()), fmt::join(allowed_keys, ", ")));
      }
    }
  }

  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
  }
  std::string_view file() const { return file_; }
  const toml::table& table() const { return table_; }

  [[noreturn]] void fail(const toml::node& at, std::string_view key, std::string_view problem) const {
    throw InvalidInput(fmt::format("{} key '{}': {}", location(file_, at.source()), key_path(key), problem));
  }

  const toml::node* optional(std::string_view key) const { return table_.get(key); }

  const toml::node& required(std::string_view key, std::string_view expected) const {
    const toml::node* node = table_.get(key);
    if (!node) {
      fail(table_, key,
           fmt::format("missing (required{}), expected {}",
                       path_.empty() ? std::string() : fmt::format(" in [{}]", path_), expected));
    }
    return *node;
  }

  Section subsection(const toml::node& node, std::string_view key,
                     std::initializer_list<std::string_view> allowed_keys) const {
    return subsection(node, key, std::vector<std::string_view>(allowed_keys));
  }
  Section subsection(const toml::node& node, std::string_view key,
                     const std::vector<std::string_view>& allowed_keys) const {
    if (!node.is_table()) {
      fail(node, key, fmt::format("{} is not a table, expected a table with keys {}", describe(node),
                                  fmt::join(allowed_keys, ", ")));
    }
    return Section(*node.as_table(), key_path(key), file_, allowed_keys);
  }

  Section required_subsection(std::string_view key, std::initializer_list<std::string_view> allowed_keys) const {
    return subsection(required(key, fmt::format("a table [{}]", key_path(key))), key, allowed_keys);
  }

  std::optional<Section> optional_subsection(std::string_view key,
                                             std::initializer_list<std::string_view> allowed_keys) const {
    return optional_subsection(key, std::vector<std::string_view>(allowed_keys));
  }
  std::optional<Section> optional_subsection(std::string_view key,
                                             const std::vector<std::string_view>& allowed_keys) const {
    const toml::node* node = optional(key);
    if (!node) return std::nullopt;
    return subsection(*node, key, allowed_keys);
  }

  // Runs a library call that throws InvalidInput naming `what`, and prefixes its message with FILE:LINE.
  template <class Call>
  auto at(const toml::node& node, Call&& call) const {
    try {
      return call();
    } catch (const InvalidInput& error) {
      throw InvalidInput(fmt::format("{} {}", location(file_, node.source()), error.what()));
    }
  }

  std::string what(std::string_view key) const { return fmt::format("key '{}'", key_path(key)); }

private:
  const toml::table& table_;
  std::string path_;
  std::string_view file_;
};

// ---- values -------------------------------------------------------------------------------------------------------

inline std::string text_of(const Section& section, const toml::node& node, std::string_view key, std::string_view expected) {
  if (!node.is_string()) section.fail(node, key, fmt::format("{} is not a string, expected {}", describe(node), expected));
  return node.as_string()->get();
}

inline double quantity_of(const Section& section, const toml::node& node, std::string_view key, Dimension dimension) {
  if (node.is_number()) {
    section.fail(node, key,
                 fmt::format("{} is a bare number without a unit, expected {}", describe(node), expected_quantity(dimension)));
  }
  if (!node.is_string()) {
    section.fail(node, key, fmt::format("{} is not a quantity, expected {}", describe(node), expected_quantity(dimension)));
  }
  const std::string text = node.as_string()->get();
  return section.at(node, [&] { return units::parse_quantity(text, dimension, section.what(key)); });
}

inline double positive_quantity_of(const Section& section, const toml::node& node, std::string_view key,
                            Dimension dimension) {
  const double value = quantity_of(section, node, key, dimension);
  if (!(value > 0)) {
    section.fail(node, key,
                 fmt::format("'{}' is not positive, expected a positive {}", node.as_string()->get(),
                             units::dimension_name(dimension)));
  }
  return value;
}

inline double positive_quantity(const Section& section, std::string_view key, Dimension dimension) {
  return positive_quantity_of(section, section.required(key, expected_quantity(dimension)), key, dimension);
}

inline std::optional<double> optional_positive_quantity(const Section& section, std::string_view key, Dimension dimension) {
  const toml::node* node = section.optional(key);
  if (!node) return std::nullopt;
  return positive_quantity_of(section, *node, key, dimension);
}

// A plain number (integer or float) >= minimum.
inline double number_at_least(const Section& section, const toml::node& node, std::string_view key, double minimum) {
  if (!node.is_number()) {
    section.fail(node, key, fmt::format("{} is not a number, expected a number >= {}", describe(node), minimum));
  }
  const double value = *node.value<double>();
  if (!std::isfinite(value) || !(value >= minimum)) {
    section.fail(node, key, fmt::format("{} is out of range, expected a number >= {}", describe(node), minimum));
  }
  return value;
}

inline std::int64_t integer_of(const Section& section, const toml::node& node, std::string_view key) {
  if (!node.is_integer()) {
    section.fail(node, key, fmt::format("{} is not an integer, expected an integer", describe(node)));
  }
  return node.as_integer()->get();
}

inline int integer_at_least(const Section& section, const toml::node& node, std::string_view key, int minimum) {
  const std::int64_t value = integer_of(section, node, key);
  if (value < minimum || value > INT_MAX) {
    section.fail(node, key, fmt::format("{} is out of range, expected an integer >= {}", value, minimum));
  }
  return static_cast<int>(value);
}

// An integer in [minimum, maximum]; `maximum` is one of the work limits of core/limits.hpp.
inline int integer_in(const Section& section, const toml::node& node, std::string_view key, int minimum, int maximum) {
  const std::int64_t value = integer_of(section, node, key);
  if (value < minimum || value > maximum) {
    section.fail(node, key, fmt::format("{} is out of range, expected an integer in [{}, {}] (the upper end is "
                                        "needlekit's work limit)",
                                        value, minimum, maximum));
  }
  return static_cast<int>(value);
}

inline bool boolean_of(const Section& section, const toml::node& node, std::string_view key) {
  if (!node.is_boolean()) section.fail(node, key, fmt::format("{} is not a boolean, expected true or false", describe(node)));
  return node.as_boolean()->get();
}

// One of the names of an enum's table (core/enum_table.hpp), the same table that the help and the JSON use.
template <class Value, std::size_t N>
Value choice_of(const Section& section, const toml::node& node, std::string_view key, const EnumTable<Value, N>& table) {
  const std::string text = text_of(section, node, key, "one of: " + choices_of(table));
  for (const EnumEntry<Value>& entry : table) {
    if (entry.name == text) return entry.value;
  }
  section.fail(node, key, fmt::format("unknown value '{}', expected one of: {}", text, choices_of(table)));
}

// Runs a library validation and reports its InvalidInput at `node`'s line.
template <class Validation>
void validate_at_node(const Section& section, const toml::node& node, Validation&& validation) {
  section.at(node, [&] {
    validation();
    return 0;
  });
}

// ---- the parts shared by both files -------------------------------------------------------------------------------

inline needle::Shape shape_of(const Section& section, std::string_view key) {
  return choice_of(section, section.required(key, "one of: " + choices_of(needle::kShapeNames)), key,
                   needle::kShapeNames);
}

inline materials::NeedleMaterial material_of(const Section& parent, std::string_view key) {
  const std::string expected =
      fmt::format("a preset name ({}) or an inline table {{ youngs_modulus = \"4 GPa\", yield_strength = \"60 MPa\", "
                  "allowable_stress = \"40 MPa\", name = \"...\" }}",
                  fmt::join(materials::material_preset_names(), ", "));
  const toml::node& node = parent.required(key, expected);
  if (node.is_string()) {
    const std::string name = node.as_string()->get();
    return parent.at(node, [&] { return materials::material_preset(name, parent.what(key)); });
  }
  if (!node.is_table()) parent.fail(node, key, fmt::format("{} is not a material, expected {}", describe(node), expected));
  const Section table =
      parent.subsection(node, key, {"name", "youngs_modulus", "yield_strength", "allowable_stress"});
  materials::NeedleMaterial material;
  material.name = "custom";
  if (const toml::node* name = table.optional("name")) material.name = text_of(table, *name, "name", "a name");
  material.youngs_modulus = positive_quantity(table, "youngs_modulus", Dimension::Pressure);
  material.yield_strength = optional_positive_quantity(table, "yield_strength", Dimension::Pressure);
  material.allowable_stress = optional_positive_quantity(table, "allowable_stress", Dimension::Pressure);
  material.source = fmt::format("inline table in {}", parent.file());
  return material;
}

// A preset name or a table { alpha, tau, small_tip_slope?, name? }; skin when the key is absent.
inline analysis::PunctureModel tissue_model_of(const Section& parent, std::string_view key) {
  const toml::node* node = parent.optional(key);
  if (!node) return analysis::skin_puncture_model();
  if (node->is_string()) {
    const std::string name = node->as_string()->get();
    return parent.at(*node, [&] { return analysis::puncture_model_preset(name, parent.what(key)); });
  }
  if (!node->is_table()) {
    parent.fail(*node, key,
                fmt::format("{} is not a tissue model, expected \"skin\", \"brain\" or a table {{ alpha = \"0.0183 N\", "
                            "tau = \"6.25 /mm\" }}",
                            describe(*node)));
  }
  const Section table = parent.subsection(*node, key, {"name", "alpha", "tau", "small_tip_slope"});
  analysis::PunctureModel model = analysis::skin_puncture_model();  // Eq 4.2's F(A) line and K are skin's
  model.name = "custom";
  if (const toml::node* name = table.optional("name")) model.name = text_of(table, *name, "name", "a name");
  model.alpha = positive_quantity(table, "alpha", Dimension::Force);
  model.tau = positive_quantity(table, "tau", Dimension::InverseLength);
  if (auto slope = optional_positive_quantity(table, "small_tip_slope", Dimension::InverseLength)) {
    model.small_tip_slope = *slope;
  }
  return model;
}

// [tissue] puncture_force = a law name (analysis::kPunctureForceLawKindNames: "eq-4.2", "romgens-2014") or a table
// { law = "linear-area", slope = "0.00019 N/um2", intercept = "-0.66 N" } | { law = "linear-diameter", slope =
// "4594 N/m", intercept = "-3 mN" } | { law = "table", tip_diameter = ["5 um", ...], force = ["20 mN", ...] },
// each with an optional valid_tip_diameter = ["min", "max"]. Eq 4.2 when the key is absent.
inline analysis::PunctureForceLaw puncture_force_law_of(const Section& parent, std::string_view key) {
  using analysis::PunctureForceLawKind;
  const toml::node* node = parent.optional(key);
  if (!node) return analysis::eq_4_2_puncture_force_law();
  const std::string expected =
      fmt::format("one of {} or a table {{ law = \"linear-area\", slope = \"0.00019 N/um2\", intercept = \"-0.66 N\" }}",
                  analysis::puncture_force_law_names());
  if (node->is_string()) {
    const std::string name = node->as_string()->get();
    const PunctureForceLawKind kind =
        parent.at(*node, [&] { return analysis::puncture_force_law_from_string(name, parent.what(key)); });
    if (kind != PunctureForceLawKind::Eq4_2 && kind != PunctureForceLawKind::Romgens2014) {
      parent.fail(*node, key, fmt::format("the law '{}' needs its coefficients, expected a table {{ law = \"{}\", ... }}",
                                          name, name));
    }
    return analysis::puncture_force_law_preset(kind);
  }
  if (!node->is_table()) parent.fail(*node, key, fmt::format("{} is not a force law, expected {}", describe(*node), expected));
  const Section table =
      parent.subsection(*node, key, {"law", "slope", "intercept", "tip_diameter", "force", "valid_tip_diameter"});
  const toml::node& law_node = table.required("law", analysis::puncture_force_law_names());
  const std::string name = text_of(table, law_node, "law", analysis::puncture_force_law_names());
  const PunctureForceLawKind kind =
      table.at(law_node, [&] { return analysis::puncture_force_law_from_string(name, table.what("law")); });
  analysis::PunctureForceLaw law = analysis::puncture_force_law_preset(kind);
  const auto quantities = [&](std::string_view array_key, Dimension dimension) {
    const toml::node& array_node =
        table.required(array_key, fmt::format("an array of {}s with units", units::dimension_name(dimension)));
    if (!array_node.is_array()) {
      table.fail(array_node, array_key, fmt::format("{} is not an array, expected [{}, ...]", describe(array_node),
                                                    example_of(dimension)));
    }
    std::vector<double> values;
    for (const toml::node& element : *array_node.as_array())
      values.push_back(quantity_of(table, element, array_key, dimension));
    return values;
  };
  const bool linear = kind == PunctureForceLawKind::LinearArea || kind == PunctureForceLawKind::LinearDiameter;
  for (std::string_view k : {"slope", "intercept"}) {
    if (!linear && table.optional(k)) {
      table.fail(*table.optional(k), k, fmt::format("does not apply to the law '{}', expected no {}", name, k));
    }
  }
  for (std::string_view k : {"tip_diameter", "force"}) {
    if (kind != PunctureForceLawKind::Table && table.optional(k)) {
      table.fail(*table.optional(k), k, fmt::format("does not apply to the law '{}', expected law = \"table\"", name));
    }
  }
  if (linear) {
    law.slope = quantity_of(table, table.required("slope", kind == PunctureForceLawKind::LinearArea ? "a force per area, e.g. \"0.00019 N/um2\"" : "a force per length, e.g. \"4594 N/m\""),
                            "slope", kind == PunctureForceLawKind::LinearArea ? Dimension::Pressure : Dimension::Stiffness);
    law.intercept = quantity_of(table, table.required("intercept", expected_quantity(Dimension::Force)), "intercept",
                                Dimension::Force);
  }
  if (kind == PunctureForceLawKind::Table) {
    law.table_tip_diameter = quantities("tip_diameter", Dimension::Length);
    law.table_force = quantities("force", Dimension::Force);
  }
  if (table.optional("valid_tip_diameter")) {
    const std::vector<double> range = quantities("valid_tip_diameter", Dimension::Length);
    if (range.size() != 2) {
      table.fail(*table.optional("valid_tip_diameter"), "valid_tip_diameter",
                 fmt::format("{} entries, expected [min, max]", range.size()));
    }
    law.valid_min_tip_diameter = range[0];
    law.valid_max_tip_diameter = range[1];
  }
  validate_at_node(table, *node, [&] { analysis::validate(law, parent.key_path(key)); });
  return law;
}

// Runs the library's validation and re-throws its InvalidInput at the line of the key it names ("needle.length: ...")
// when that key is in the file, otherwise at `fallback`'s line.
template <class Validation>
void validate_at_keys(const toml::table& root, std::string_view file, const toml::node& fallback,
                      Validation&& validation) {
  try {
    validation();
  } catch (const InvalidInput& error) {
    const std::string_view message = error.what();
    const std::size_t colon = message.find(": ");
    if (colon != std::string_view::npos) {
      const std::string_view key = message.substr(0, colon);
      if (const toml::node* node = root.at_path(key).node()) {
        throw InvalidInput(
            fmt::format("{} key '{}': {}", location(file, node->source()), key, message.substr(colon + 2)));
      }
    }
    throw InvalidInput(fmt::format("{} {}", location(file, fallback.source()), message));
  }
}

inline std::string read_text(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw IoError(fmt::format("{}: cannot read: it is a directory", path.string()));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot read: {}", path.string(), std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError(fmt::format("{}: cannot read: {}", path.string(), std::strerror(errno)));
  return text.str();
}

inline toml::table parse_toml(std::string_view text, std::string_view file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& error) {
    throw IoError(fmt::format("{}:{}:{}: invalid TOML: {}", file, error.source().begin.line,
                              error.source().begin.column, error.description()));
  }
}

// ---- the needle --------------------------------------------------------------------------------------------------

inline needle::NeedleGeometry needle_of(const Section& section) {
  needle::NeedleGeometry geometry;
  geometry.shape = shape_of(section, "shape");
  geometry.tip_diameter = positive_quantity(section, "tip_diameter", Dimension::Length);
  if (geometry.shape == needle::Shape::Cylinder) {
    geometry.base_diameter = optional_positive_quantity(section, "base_diameter", Dimension::Length)
                                 .value_or(geometry.tip_diameter);
  } else {
    geometry.base_diameter = positive_quantity(section, "base_diameter", Dimension::Length);
  }
  geometry.bore_diameter = optional_positive_quantity(section, "bore_diameter", Dimension::Length).value_or(0.0);
  geometry.length = positive_quantity(section, "length", Dimension::Length);
  return geometry;
}

}  // namespace needlekit::io::config
