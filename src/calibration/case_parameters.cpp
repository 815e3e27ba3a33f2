#include "needlekit/calibration/case_parameters.hpp"

#include <toml++/toml.h>

#include <array>
#include <fmt/format.h>
#include <sstream>
#include <vector>

#include "needlekit/core/errors.hpp"

namespace needlekit::calibration {
namespace {

constexpr std::array<ParameterKind, 12> kKinds{{
    {"tissue.layers.N.youngs_modulus", "Young's modulus of tissue layer N (indent/insert cases)"},
    {"tissue.layers.N.poisson_ratio", "Poisson ratio of tissue layer N (indent/insert cases)"},
    {"puncture.critical_pressure", "critical pressure P_c of the puncture criterion (indent/insert cases)"},
    {"puncture.toughness", "fracture toughness J of the puncture criterion (indent/insert cases)"},
    {"post_puncture.stiffness", "K of the post-puncture load K*S (insert cases; only K*S is identifiable)"},
    {"post_puncture.scale", "S of the post-puncture load K*S (insert cases; only K*S is identifiable)"},
    {"tissue.model.alpha", "alpha of F(d) = alpha*exp(tau*d), Eq 4.1 (design files)"},
    {"tissue.model.tau", "tau of F(d) = alpha*exp(tau*d), Eq 4.1 (design files)"},
    {"tissue.model.small_tip_slope", "K of the small-tip line d = K*A (design files)"},
    {"tissue.puncture_force.slope", "slope of a linear puncture-force law (design files)"},
    {"tissue.puncture_force.intercept", "intercept of a linear puncture-force law (design files)"},
    {"tissue.puncture_force.force.N", "force N of a table puncture-force law (design files)"},
}};

std::vector<std::string> segments(std::string_view path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    parts.emplace_back(path.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start));
    if (dot == std::string_view::npos) return parts;
    start = dot + 1;
  }
}

bool is_index(std::string_view part) {
  return !part.empty() && part.find_first_not_of("0123456789") == std::string_view::npos;
}

// "a.b.0.c" -> "a.b[0].c" (toml++'s path syntax).
std::string toml_path(std::string_view path) {
  std::string out;
  for (const std::string& part : segments(path)) {
    if (is_index(part)) {
      out += "[" + part + "]";
    } else {
      out += (out.empty() ? "" : ".") + part;
    }
  }
  return out;
}

std::optional<units::Dimension> dimension_of_unit(std::string_view unit) {
  for (units::Dimension d : {units::Dimension::Length, units::Dimension::Area, units::Dimension::Volume,
                             units::Dimension::Force, units::Dimension::Pressure, units::Dimension::Energy,
                             units::Dimension::Angle, units::Dimension::InverseLength, units::Dimension::Stiffness}) {
    try {
      units::unit_factor(unit, d, "unit");
      return d;
    } catch (const InvalidInput&) {
    }
  }
  return std::nullopt;
}

// Byte offset of (line, column), both 1-based, in `text`.
std::size_t offset_of(std::string_view text, unsigned line, unsigned column) {
  std::size_t offset = 0;
  for (unsigned l = 1; l < line; ++l) offset = text.find('\n', offset) + 1;
  return offset + column - 1;
}

}  // namespace

std::span<const ParameterKind> parameter_kinds() { return kKinds; }

const ParameterKind* parameter_kind_of(std::string_view path) {
  const std::vector<std::string> parts = segments(path);
  for (const ParameterKind& kind : kKinds) {
    const std::vector<std::string> pattern = segments(kind.pattern);
    if (pattern.size() != parts.size()) continue;
    bool match = true;
    for (std::size_t i = 0; i < parts.size() && match; ++i)
      match = pattern[i] == "N" ? is_index(parts[i]) : pattern[i] == parts[i];
    if (match) return &kind;
  }
  return nullptr;
}

std::string parameter_kind_list() {
  std::string list;
  for (const ParameterKind& kind : kKinds) list += fmt::format("{}{}", list.empty() ? "" : ", ", kind.pattern);
  return list;
}

std::string unit_of(std::string_view text) {
  const std::size_t end = text.find_last_not_of(" \t");
  if (end == std::string_view::npos) return {};
  std::size_t start = text.find_first_not_of(" \t");
  std::size_t i = start;
  while (i <= end && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.' || text[i] == '-' ||
                      text[i] == '+' || ((text[i] == 'e' || text[i] == 'E') && i + 1 <= end &&
                                         (std::isdigit(static_cast<unsigned char>(text[i + 1])) ||
                                          text[i + 1] == '-' || text[i + 1] == '+'))))
    ++i;
  while (i <= end && (text[i] == ' ' || text[i] == '\t')) ++i;
  return std::string(text.substr(i, end + 1 - i));
}

std::optional<CaseValue> case_value(std::string_view case_text, std::string_view path, std::string_view source_name) {
  toml::table root;
  try {
    root = toml::parse(case_text, source_name);
  } catch (const toml::parse_error& error) {
    throw IoError(fmt::format("{}:{}: invalid TOML: {}", source_name, error.source().begin.line, error.description()));
  }
  const toml::node* node = root.at_path(toml_path(path)).node();
  if (!node) return std::nullopt;
  CaseValue value;
  value.line = static_cast<int>(node->source().begin.line);
  if (node->is_number()) {
    value.value = *node->value<double>();
    return value;
  }
  if (!node->is_string()) return std::nullopt;
  const std::string text = node->as_string()->get();
  const std::optional<units::Dimension> dimension = dimension_of_unit(unit_of(text));
  if (!dimension) return std::nullopt;
  value.dimension = *dimension;
  value.value = units::parse_quantity(text, *dimension, path);
  return value;
}

std::string with_case_value(std::string_view case_text, std::string_view path, double value, units::Dimension dimension,
                            std::string_view unit, int significant_digits) {
  const toml::table root = toml::parse(case_text);
  const toml::node* node = root.at_path(toml_path(path)).node();
  if (!node) throw InvalidInput(fmt::format("{}: no such key in the case", path));
  const toml::source_region& region = node->source();
  const std::size_t begin = offset_of(case_text, region.begin.line, region.begin.column);
  const std::size_t end = offset_of(case_text, region.end.line, region.end.column);
  std::string replacement;
  if (dimension == units::Dimension::Dimensionless) {
    replacement = fmt::format("{:.{}g}", value, significant_digits);
    if (replacement.find_first_of(".eEn") == std::string::npos) replacement += ".0";  // stays a TOML float
  } else {
    const std::string_view symbol = unit.empty() ? units::si_symbol(dimension) : unit;
    const double in_unit = value / units::unit_factor(symbol, dimension, path);
    replacement = fmt::format("\"{:.{}g} {}\"", in_unit, significant_digits, symbol);
  }
  std::string text(case_text);
  text.replace(begin, end - begin, replacement);
  return text;
}

}  // namespace needlekit::calibration
