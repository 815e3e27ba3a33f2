// Every Python enum of the module comes from its enum's table (core/enum_table.hpp) through bind_enum: the members
// are the C++ enumerators, in their declaration order and with their identifiers ("None" becomes "None_", which
// Python reserves), and each member's docstring is its table row, `"name": meaning`, the name being the text that
// files, the command line and JSON use. An enumerator without a row, or a row without an enumerator, does not
// compile; python/tests/test_enums.py checks that no enum of the module was bound another way.
#pragma once
#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/enumerator_name.hpp"

namespace needlekit::python {

namespace detail {
// The identifier of a C++ enumerator as a Python attribute name.
inline std::string python_member_name(std::string_view identifier) {
  return identifier == "None" ? "None_" : std::string(identifier);
}

template <const auto& Table, auto Value>
consteval bool has_row() {
  for (const auto& entry : Table) {
    if (entry.value == Value) return true;
  }
  return false;
}
}  // namespace detail

// Binds py::enum_<Enum> named `name` from `Table` (an EnumTable of Enum with a row per enumerator). Limit bounds the
// values scanned for enumerators (core/enumerator_name.hpp): raise it for an enum with a value of Limit or more.
template <const auto& Table, std::size_t Limit = 64>
auto bind_enum(pybind11::module_& m, const char* name, const char* doc) {
  using Enum = decltype(Table[0].value);
  static constexpr auto kEnumerators = named_enumerators<Enum, Limit>();
  static_assert(kEnumerators.size() == Table.size(), "the enum's table needs one row per enumerator");
  pybind11::enum_<Enum> binding(m, name, doc);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    static_assert((detail::has_row<Table, kEnumerators[I]>() && ...), "an enumerator has no row in the enum's table");
    (binding.value(detail::python_member_name(enumerator_name<kEnumerators[I]>()).c_str(), kEnumerators[I],
                   fmt::format("\"{}\": {}", name_of(Table, kEnumerators[I]), meaning_of(Table, kEnumerators[I]))
                       .c_str()),
     ...);
  }(std::make_index_sequence<kEnumerators.size()>{});
  return binding;
}

}  // namespace needlekit::python
