// Internal to the uncertainty folder: lookups in the {value, "name", "meaning"} tables that declare each enum once.
#pragma once
#include <fmt/format.h>

#include <string_view>
#include <vector>

#include "needlekit/core/errors.hpp"

namespace needlekit::uncertainty::detail {

// The name of `value` in `table` (whose entries hold it in `field`), "?" if absent.
template <class Info, class Value>
std::string_view name_of(const std::vector<Info>& table, Value Info::*field, Value value) {
  for (const Info& entry : table) {
    if (entry.*field == value) return entry.name;
  }
  return "?";
}

// The value named `name`; throws InvalidInput "WHAT: unknown NOUN 'NAME', expected one of: ..." otherwise.
template <class Info, class Value>
Value value_named(const std::vector<Info>& table, Value Info::*field, std::string_view name, std::string_view what,
                  std::string_view noun) {
  std::vector<std::string_view> names;
  for (const Info& entry : table) {
    if (entry.name == name) return entry.*field;
    names.push_back(entry.name);
  }
  throw InvalidInput(fmt::format("{}: unknown {} '{}', expected one of: {}", what, noun, name, fmt::join(names, ", ")));
}

}  // namespace needlekit::uncertainty::detail
