// Python properties from a parameter table (core/parameter.hpp): every row of the table becomes a property of the
// bound class, named after the field, with its unit, range, meaning and default as its docstring; the class's
// docstring lists every keyword of its constructor. Quantities accept strings with units ("1e-9 m") as well as SI floats.
#pragma once
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "common.hpp"
#include "needlekit/core/parameter_text.hpp"

namespace needlekit::python {

// The docstring of a row's property: a negated flag's is the field's (the negation of the file's key).
template <class Options, class Row>
std::string property_docstring(const Row& row, const ParameterText& text) {
  if constexpr (requires { row.negated; }) {
    if (row.negated) {
      return fmt::format("true | false: the negation of the case file's {}: not ({}). Default: {}.", text.key,
                         row.meaning, Options{}.*row.field ? "true" : "false");
    }
  }
  return docstring_of(text);
}

// The properties of the table's rows on `cls` (whose class may derive from Options), and their lines for the class's
// docstring ("\n  name: doc" each).
template <class Options, class Class, class Table>
std::string def_parameter_properties(Class& cls, const Table& table) {
  const std::vector<ParameterText> texts = parameter_texts<Options>(table);
  std::string keywords;
  std::size_t index = 0;
  for_each_parameter(table, [&](const auto& row) {
    const ParameterText& text = texts[index++];
    const std::string doc = property_docstring<Options>(row, text);
    const char* name = row.attribute().data();  // the views of the table's string literals end in '\0'
    keywords += fmt::format("\n  {}: {}", text.name, doc);
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(row.field)>, std::optional<double> Options::*>) {
      def_optional_quantity(cls, name, row.field, row.dimension, doc.c_str());  // None: not given
      return;
    }
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(row.field)>, double Options::*>) {
      if (row.dimension != Dimension::Dimensionless) {  // the bound class's member: Options may be its base
        def_quantity(cls, name, static_cast<double Class::type::*>(row.field), row.dimension, doc.c_str());
        return;
      }
    }
    cls.def_readwrite(name, row.field, doc.c_str());
  });
  return keywords;
}

// Every row a property, the keyword constructor, and the keywords in the class's docstring.
template <class Options, class Class, class Table>
void def_parameters(Class& cls, const Table& table) {
  const std::string keywords = def_parameter_properties<Options>(cls, table);
  def_keyword_init<Options>(cls);
  cls.doc() = std::string(py::str(cls.doc())) + "\n\nKeywords (every field):" + keywords;
}

}  // namespace needlekit::python
