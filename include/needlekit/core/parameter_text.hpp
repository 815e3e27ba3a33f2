// The rows of a parameter table (core/parameter.hpp) as text: what `needlekit describe`, the CLI help,
// docs/reference.md and the Python docstrings show, all from this one conversion.
#pragma once
#include <fmt/format.h>

#include <string>
#include <vector>

#include "needlekit/core/parameter.hpp"

namespace needlekit {

struct ParameterText {
  std::string key;           // "solver.friction": the file's table and key (the bare key for a row in no file)
  std::string name;          // the field in C++ and Python
  std::string kind;          // "number", "integer", "boolean", "choice", or "quantity (length)"
  std::string unit;          // the SI unit of a quantity, "" for a pure number
  std::string default_text;  // as a file writes it: 1e-06, "1e-09 m", true, "secant"
  std::string range;         // "in (0, 1)", ">= 0", "true | false", "\"a\" | \"b\""
  std::string meaning;       // one line
  std::string choices;       // a choice's names, one line each with its meaning ("" otherwise)
  bool required = false;     // files must give it: default_text is then the struct's initializer, Python's default
  bool optional = false;     // an optional quantity: files may leave it out (default_text is Python's None)
  std::string file_default() const {  // what a file gets without it
    return required ? "required" : optional ? "optional" : default_text;
  }
};

namespace detail {
inline std::string dotted_key(std::string_view group, std::string_view key) {
  return group.empty() ? std::string(key) : fmt::format("{}.{}", group, key);
}
template <class Options, class Value>
ParameterText text_of_row(const Parameter<Options, Value>& row, const Options& defaults) {
  const double value = static_cast<double>(defaults.*row.field);
  const bool quantity = row.dimension != units::Dimension::Dimensionless;
  const std::string unit = quantity ? std::string(units::si_symbol(row.dimension)) : "";
  return {dotted_key(row.group, row.key), std::string(row.attribute()),
          quantity ? fmt::format("quantity ({})", units::dimension_name(row.dimension))
                   : (std::is_integral_v<Value> ? "integer" : "number"),
          unit, quantity ? fmt::format("\"{:g} {}\"", value, unit) : fmt::format("{:g}", value),
          quantity ? fmt::format("{} {}", row.range(), unit) : row.range(), std::string(row.meaning), "",
          row.required};
}
// A negated flag's default is the file's (the negation of the field's), its meaning the key's and then the field's.
template <class Options>
ParameterText text_of_row(const Flag<Options>& row, const Options& defaults) {
  const bool file_value = row.negated ? !(defaults.*row.field) : defaults.*row.field;
  return {dotted_key(row.group, row.key), std::string(row.attribute()), "boolean", "", file_value ? "true" : "false",
          "true | false",
          row.negated ? fmt::format("{} ({} in Python is its negation)", row.meaning, row.attribute())
                      : std::string(row.meaning),
          ""};
}
template <class Options, class Value, std::size_t N>
ParameterText text_of_row(const Choice<Options, Value, N>& row, const Options& defaults) {
  return {dotted_key(row.group, row.key), std::string(row.attribute()), "choice", "",
          fmt::format("\"{}\"", name_of(*row.names, defaults.*row.field)), choices_of(*row.names),
          std::string(row.meaning), meanings_of(*row.names, row.key), row.required};
}
// An optional quantity: "optional quantity (pressure)", its default Python's None (or the value `defaults` gives).
template <class Options>
ParameterText text_of_row(const OptionalQuantity<Options>& row, const Options& defaults) {
  const std::string unit(units::si_symbol(row.dimension));
  const std::optional<double> value = defaults.*row.field;
  ParameterText text{dotted_key(row.group, row.key), std::string(row.attribute()),
                     fmt::format("optional quantity ({})", units::dimension_name(row.dimension)), unit,
                     value ? fmt::format("\"{:g} {}\"", *value, unit) : "None",
                     fmt::format("{} {}", row.range(), unit), std::string(row.meaning), ""};
  text.optional = true;
  return text;
}
}  // namespace detail

// One text per row, in the table's order; `defaults` supplies the defaults shown (Options{} for the struct's own,
// or the defaults a case file starts from).
template <class Options, class Table>
std::vector<ParameterText> parameter_texts(const Table& table, const Options& defaults = Options{}) {
  std::vector<ParameterText> texts;
  for_each_parameter(table, [&](const auto& row) { texts.push_back(detail::text_of_row(row, defaults)); });
  return texts;
}

// "(0, 1): meaning. Default: 1e-06." for a docstring or a help line.
inline std::string docstring_of(const ParameterText& text) {
  return fmt::format("{}{}: {}. Default: {}{}.", text.unit.empty() ? "" : text.unit + ", ", text.range, text.meaning,
                     text.default_text, text.required ? " (required in files)" : "");
}

}  // namespace needlekit
