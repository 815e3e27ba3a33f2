// One table per enum: {value, "name", "one-line meaning"}, declared once beside the enum. Every place that turns the
// enum into text or back — to_string, the config readers, the list of accepted names in error messages, the CLI help
// and the JSON writers — reads the table, so they cannot drift apart. Every enum that has a text has a table (the
// enum-table test finds an enumerator without a row), the Python module binds each enum from its table
// (python/src/enum_binding.hpp), and every `to_string(Enum)` returns name_of's std::string_view: the tables are
// constexpr, so the text lives as long as the program, and a caller that needs a std::string makes one.
//
//   inline constexpr EnumTable<Shape, 3> kShapeNames{{
//       {Shape::Cylinder, "cylinder", "constant diameter D1 = D2"}, ...}};
//   name_of(kShapeNames, Shape::Cone) == "cone";  value_of(kShapeNames, "cone", "needle.shape") == Shape::Cone
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "needlekit/core/errors.hpp"

namespace needlekit {

template <class Value>
struct EnumEntry {
  Value value;
  std::string_view name;     // as written in files, on the command line and in JSON
  std::string_view meaning;  // one line, for the help
};

template <class Value, std::size_t N>
using EnumTable = std::array<EnumEntry<Value>, N>;

// The name of `value` ("?" if the table lacks it: a defect that the enum-table tests catch).
template <class Value, std::size_t N>
constexpr std::string_view name_of(const EnumTable<Value, N>& table, Value value) {
  for (const EnumEntry<Value>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "?";
}

// The one-line meaning of `value` ("" if the table lacks it).
template <class Value, std::size_t N>
constexpr std::string_view meaning_of(const EnumTable<Value, N>& table, Value value) {
  for (const EnumEntry<Value>& entry : table) {
    if (entry.value == value) return entry.meaning;
  }
  return "";
}

// The accepted names as the help and error messages show them: "a" | "b" | "c".
template <class Value, std::size_t N>
std::string choices_of(const EnumTable<Value, N>& table) {
  std::string text;
  for (const EnumEntry<Value>& entry : table) {
    if (!text.empty()) text += " | ";
    text += '"';
    text += entry.name;
    text += '"';
  }
  return text;
}

// One line per name with its meaning, `  KEY = "name": meaning` (for a command's help).
template <class Value, std::size_t N>
std::string meanings_of(const EnumTable<Value, N>& table, std::string_view key) {
  std::string text;
  for (const EnumEntry<Value>& entry : table) {
    text += "  ";
    text += key;
    text += " = \"";
    text += entry.name;
    text += "\": ";
    text += entry.meaning;
    text += '\n';
  }
  return text;
}

// The value named `name`; throws InvalidInput "WHAT: unknown value 'NAME', expected one of: "a" | "b"".
template <class Value, std::size_t N>
Value value_of(const EnumTable<Value, N>& table, std::string_view name, std::string_view what) {
  for (const EnumEntry<Value>& entry : table) {
    if (entry.name == name) return entry.value;
  }
  throw InvalidInput(std::string(what) + ": unknown value '" + std::string(name) + "', expected one of: " +
                     choices_of(table));
}

}  // namespace needlekit
