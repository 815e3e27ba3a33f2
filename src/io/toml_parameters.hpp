// Reading the rows of a parameter table (core/parameter.hpp) from one table of a TOML file, with the messages of
// toml_config.hpp: FILE:LINE: key 'solver.friction': -1.0 is out of range, expected a number >= 0.
#pragma once
#include <climits>
#include <string_view>
#include <vector>

#include "needlekit/core/parameter.hpp"
#include "needlekit/io/toml_config.hpp"

namespace needlekit::io::config {

template <class Options>
double value_of_row(const Section& section, const toml::node& node, const Parameter<Options, double>& row) {
  if (row.dimension != Dimension::Dimensionless) {
    const double value = quantity_of(section, node, row.key, row.dimension);
    if (!row.accepts(value)) {
      section.fail(node, row.key,
                   fmt::format("'{}' is out of range, expected a {} {} {}", node.as_string()->get(),
                               units::dimension_name(row.dimension), row.range(), units::si_symbol(row.dimension)));
    }
    return value;
  }
  if (!node.is_number()) {
    section.fail(node, row.key, fmt::format("{} is not a number, expected a number {}", describe(node), row.range()));
  }
  const double value = *node.value<double>();
  if (!row.accepts(value)) {
    section.fail(node, row.key, fmt::format("{} is out of range, expected a number {}", describe(node), row.range()));
  }
  return value;
}

template <class Options>
int value_of_row(const Section& section, const toml::node& node, const Parameter<Options, int>& row) {
  const std::int64_t value = integer_of(section, node, row.key);
  if (!row.accepts(static_cast<double>(value)) || value > INT_MAX) {
    section.fail(node, row.key, fmt::format("{} is out of range, expected an integer {}", value, row.range()));
  }
  return static_cast<int>(value);
}

template <class Options>
bool value_of_row(const Section& section, const toml::node& node, const Flag<Options>& row) {
  return boolean_of(section, node, row.key);
}

template <class Options, class Value, std::size_t N>
Value value_of_row(const Section& section, const toml::node& node, const Choice<Options, Value, N>& row) {
  return choice_of(section, node, row.key, *row.names);
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

// Sets the field of every row of `group` whose key the section has; the fields of the others keep their values.
template <class Options, class Table>
void read_parameters(const Section& section, const Table& table, std::string_view group, Options& options) {
  for_each_parameter(table, [&](const auto& row) {
    if (row.group != group) return;
    if (const toml::node* node = section.optional(row.key)) options.*row.field = value_of_row(section, *node, row);
  });
}

}  // namespace needlekit::io::config
