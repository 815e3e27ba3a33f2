// The C++ identifier of an enumerator ("Cylinder" for needle::Shape::Cylinder), known at compile time: what the
// Python module names its enum members, and what the enum-table test uses to find enumerators that a table lacks.
// C++20 has no reflection; like magic_enum, this reads the compiler's text of a template argument, which g++ prints
// as "... [with auto Value = needlekit::needle::Shape::Cylinder; ...]" for a named enumerator and as
// "(needlekit::needle::Shape)7" for a value no enumerator has.
//
//   enumerator_name<needle::Shape::Cone>() == "Cone";  enumerator_name<static_cast<needle::Shape>(7)>() == ""
#pragma once
#include <array>
#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>

namespace needlekit {

namespace detail {
template <auto Value>
consteval std::string_view template_argument_text() {
  const std::string_view signature = __PRETTY_FUNCTION__;
  const std::string_view marker = "Value = ";
  const std::size_t begin = signature.find(marker) + marker.size();
  const std::size_t end = signature.find_first_of(";]", begin);
  return signature.substr(begin, end - begin);
}
}  // namespace detail

// The identifier of the enumerator `Value`, or "" if no enumerator of its type has this value.
template <auto Value>
  requires std::is_enum_v<decltype(Value)>
consteval std::string_view enumerator_name() {
  const std::string_view text = detail::template_argument_text<Value>();
  if (text.starts_with('(')) return {};
  return text.substr(text.rfind("::") + 2);
}

// The values 0 .. Limit-1 of Enum that name an enumerator, in order (Limit bounds the compile-time scan).
template <class Enum, std::size_t Limit = 64>
  requires std::is_enum_v<Enum>
consteval auto named_enumerators() {
  constexpr auto named = []<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<bool, Limit>{!enumerator_name<static_cast<Enum>(I)>().empty()...};
  }(std::make_index_sequence<Limit>{});
  constexpr std::size_t count = [&] {
    std::size_t n = 0;
    for (bool is_named : named) n += is_named ? 1 : 0;
    return n;
  }();
  std::array<Enum, count> values{};
  std::size_t next = 0;
  for (std::size_t i = 0; i < Limit; ++i) {
    if (named[i]) values[next++] = static_cast<Enum>(i);
  }
  return values;
}

}  // namespace needlekit
