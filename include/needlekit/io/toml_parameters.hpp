// Reading the rows of a parameter table (core/parameter.hpp) from one table of a TOML file, with the messages of
// toml_config.hpp: FILE:LINE: key 'solver.friction': -1.0 is out of range, expected a number >= 0.
#pragma once
#include <climits>
#include <cstdint>
#include <type_traits>
#include <string_view>
#include <vector>

#include "needlekit/core/parameter.hpp"
#include "needlekit/io/toml_config.hpp"

namespace needlekit::io::config {

namespace detail {
// "[0, 90) deg" for a row's two-sided range in the unit of the value's text ("90 deg"), so that the message compares
// like with like.
template <class Row>
std::string range_in_unit_of(const Row& row, std::string_view text) {
  const std::size_t unit_start = text.find_first_not_of("+-0123456789.eE ");
  const std::string_view unit = unit_start == std::string_view::npos ? "" : text.substr(unit_start);
  const double factor = units::unit_factor(unit, row.dimension, row.key);
  return fmt::format("{}{:g}, {:g}{} {}", row.min_bound == Bound::Open ? '(' : '[', row.min / factor,
                     row.max / factor, row.max_bound == Bound::Open ? ')' : ']', unit);
}
}  // namespace detail

// A quantity: written with a unit; a value outside the row's range is refused as "is not positive" for (0, inf),
// in the value's own unit for a two-sided range, else against the range in SI. Row: a quantity's Parameter or an
// OptionalQuantity.
template <class Row>
double quantity_of_row(const Section& section, const toml::node& node, const Row& row) {
  if (row.min == 0 && row.min_bound == Bound::Open && !std::isfinite(row.max)) {
    return positive_quantity_of(section, node, row.key, row.dimension);
  }
  const double value = quantity_of(section, node, row.key, row.dimension);
  if (row.accepts(value)) return value;
  const std::string& text = node.as_string()->get();
  if (std::isfinite(row.min) && std::isfinite(row.max)) {
    section.fail(node, row.key,
                 fmt::format("{} is outside {}, expected the {} {} {}", text, detail::range_in_unit_of(row, text),
                             units::dimension_name(row.dimension), row.range(), units::si_symbol(row.dimension)));
  }
  section.fail(node, row.key,
               fmt::format("'{}' is out of range, expected a {} {} {}", text, units::dimension_name(row.dimension),
                           row.range(), units::si_symbol(row.dimension)));
}

template <class Options>
double value_of_row(const Section& section, const toml::node& node, const Parameter<Options, double>& row) {
  if (row.dimension != Dimension::Dimensionless) return quantity_of_row(section, node, row);
  if (!node.is_number()) {
    section.fail(node, row.key, fmt::format("{} is not a number, expected a number {}", describe(node), row.range()));
  }
  const double value = *node.value<double>();
  if (!row.accepts(value)) {
    section.fail(node, row.key, fmt::format("{} is out of range, expected a number {}", describe(node), row.range()));
  }
  return value;
}

// An optional quantity given in the file.
template <class Options>
double value_of_row(const Section& section, const toml::node& node, const OptionalQuantity<Options>& row) {
  return quantity_of_row(section, node, row);
}

// An integer; a finite upper end is a work limit (core/limits.hpp) and the message says so.
template <class Options>
int value_of_row(const Section& section, const toml::node& node, const Parameter<Options, int>& row) {
  const std::int64_t value = integer_of(section, node, row.key);
  if (!row.accepts(static_cast<double>(value)) || value > INT_MAX) {
    section.fail(node, row.key,
                 fmt::format("{} is out of range, expected an integer {}{}", value, row.range(),
                             std::isfinite(row.max) ? " (the upper end is needlekit's work limit)" : ""));
  }
  return static_cast<int>(value);
}

// An unsigned count or seed (std::size_t, std::uint64_t): TOML's integers are signed, so at most 2^63 - 1.
template <class Options, class Value>
  requires std::is_unsigned_v<Value>
Value value_of_row(const Section& section, const toml::node& node, const Parameter<Options, Value>& row) {
  const std::int64_t value = integer_of(section, node, row.key);
  if (value < 0 || !row.accepts(static_cast<double>(value))) {
    section.fail(node, row.key,
                 fmt::format("{} is out of range, expected an integer {}{}", value, row.range(),
                             std::isfinite(row.max) ? " (the upper end is needlekit's work limit)" : ""));
  }
  return static_cast<Value>(value);
}

template <class Options>
bool value_of_row(const Section& section, const toml::node& node, const Flag<Options>& row) {
  return boolean_of(section, node, row.key) != row.negated;
}

template <class Options, class Value, std::size_t N>
Value value_of_row(const Section& section, const toml::node& node, const Choice<Options, Value, N>& row) {
  return choice_of(section, node, row.key, *row.names);
}

// What a required row's missing key expects: a quantity with its unit, or one of a choice's names.
template <class Row>
std::string expected_of_row(const Row& row) {
  if constexpr (requires { row.names; }) {
    return "one of: " + choices_of(*row.names);
  } else {
    return expected_quantity(row.dimension);
  }
}

// The keys of the rows written in the file's table `group`.
template <class Table>
std::vector<std::string_view> keys_of_group(const Table& table, std::string_view group) {
  std::vector<std::string_view> keys;
  for_each_parameter(table, [&](const auto& row) {
    if (row.group == group) keys.push_back(row.key);
  });
  return keys;
}

// Sets the field of every row of `group` whose key the section has; the fields of the others keep their values. A
// required row's key missing is an error.
template <class Options, class Table>
void read_parameters(const Section& section, const Table& table, std::string_view group, Options& options) {
  for_each_parameter(table, [&](const auto& row) {
    if (row.group != group) return;
    if constexpr (requires { row.required; }) {
      if (row.required) section.required(row.key, expected_of_row(row));
    }
    if (const toml::node* node = section.optional(row.key)) options.*row.field = value_of_row(section, *node, row);
  });
}

}  // namespace needlekit::io::config
