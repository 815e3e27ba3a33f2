// One declaration per parameter (FEBio's parameter lists are the model): the key it has in files, the field of the
// Options struct it sets (whose initializer is the default: declared there, nowhere else), its valid range, its unit
// and a one-line meaning. An Options struct's table is a std::tuple of such rows, one per field, of three kinds:
//   Parameter<Options, double|int>  a number, with its range and (for a quantity) its dimension; a finite upper
//                                   end of an integer is one of needlekit's work limits (core/limits.hpp)
//   Flag<Options>                   true or false
//   Choice<Options, Enum, N>        one of the names of an enum's table (core/enum_table.hpp)
//   OptionalQuantity<Options>       a quantity that may be not given (std::optional<double>, empty by default)
// A range's infinite end is open unless a double row closes it on purpose: (0, inf] admits inf (a cap switched off).
// The config readers, their range checks, the validation of the struct, the CLI help, `needlekit describe`,
// docs/reference.md and the Python keyword arguments all read the table (core/parameter_text.hpp turns rows into
// text), and a test checks with field_count that every field of the struct has a row.
//
//   inline constexpr std::tuple kSolverParameters{
//       Parameter<SolverOptions, double>{"residual_tolerance", &SolverOptions::residual_tolerance, 0, 1, Bound::Open,
//                                        Bound::Open, "Newton: ...", "solver"},
//       Flag<SolverOptions>{"two_pass", &SolverOptions::two_pass, "surface contact: ...", "solver"}, ...};
#pragma once
#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/units.hpp"

namespace needlekit {

enum class Bound { Open, Closed };
inline constexpr double kNoLimit = std::numeric_limits<double>::infinity();

template <class Options, class Value>
struct Parameter {
  std::string_view key;
  Value Options::*field;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  Bound min_bound = Bound::Closed;
  Bound max_bound = Bound::Closed;
  std::string_view meaning;
  std::string_view group = "";  // the table of the file it is written in ("solver"); "" for none
  units::Dimension dimension = units::Dimension::Dimensionless;  // a quantity: written with a unit in files
  std::string_view name = "";   // the field's name in C++ and Python where it is not the key
  bool required = false;        // files must give it (the struct's initializer is then Python's default only)

  std::string_view attribute() const { return name.empty() ? key : name; }

  // The default: the field's initializer in Options.
  Value default_value() const { return Options{}.*field; }

  // An infinite value only at an infinite end that is closed ("(0, inf]": a cap that may be switched off).
  bool accepts(double value) const {
    if (std::isnan(value)) return false;
    if (std::isinf(value)) {
      return std::is_floating_point_v<Value> && value == (value > 0 ? max : min) &&
             (value > 0 ? max_bound : min_bound) == Bound::Closed;
    }
    const bool above = min_bound == Bound::Open ? value > min : value >= min;
    const bool below = max_bound == Bound::Open ? value < max : value <= max;
    return above && below;
  }

  // "in (0, 1)", ">= 1", "> 0", "in (0, inf]".
  std::string range() const {
    constexpr bool kMayBeInfinite = std::is_floating_point_v<Value>;  // an int row's closed kNoLimit means "no limit"
    const bool has_min = std::isfinite(min) || (kMayBeInfinite && min_bound == Bound::Closed);
    const bool has_max = std::isfinite(max) || (kMayBeInfinite && max_bound == Bound::Closed);
    if (has_min && has_max) {
      return fmt::format("in {}{:g}, {:g}{}", min_bound == Bound::Open ? '(' : '[', min, max,
                         max_bound == Bound::Open ? ')' : ']');
    }
    if (has_min) return fmt::format("{} {:g}", min_bound == Bound::Open ? ">" : ">=", min);
    if (has_max) return fmt::format("{} {:g}", max_bound == Bound::Open ? "<" : "<=", max);
    return "any";
  }
};

template <class Options>
struct Flag {
  std::string_view key;
  bool Options::*field;
  std::string_view meaning;  // of the key as files write it
  std::string_view group = "";
  std::string_view name = "";
  bool negated = false;  // the file's key is the field's negation ([loading] continue_after_puncture: stop_at_puncture)

  std::string_view attribute() const { return name.empty() ? key : name; }
};

template <class Options, class Value, std::size_t N>
struct Choice {
  std::string_view key;
  Value Options::*field;
  const EnumTable<Value, N>* names;
  std::string_view meaning;
  std::string_view group = "";
  std::string_view name = "";
  bool required = false;  // files must give it (the struct's initializer is then Python's default only)

  std::string_view attribute() const { return name.empty() ? key : name; }
};

// A quantity that files and Python may leave out ([puncture] critical_pressure: the criterion is then not used): a
// std::optional<double> field, empty in Options{}, with no default; its range applies to a given value.
template <class Options>
struct OptionalQuantity {
  std::string_view key;
  std::optional<double> Options::*field;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  Bound min_bound = Bound::Closed;
  Bound max_bound = Bound::Closed;
  std::string_view meaning;
  std::string_view group = "";
  units::Dimension dimension = units::Dimension::Dimensionless;
  std::string_view name = "";

  std::string_view attribute() const { return name.empty() ? key : name; }
  // The same range as a number row: one set of rules for both.
  Parameter<Options, double> as_number() const {
    return {key, nullptr, min, max, min_bound, max_bound, meaning, group, dimension, name};
  }
  bool accepts(double value) const { return as_number().accepts(value); }
  std::string range() const { return as_number().range(); }
};

// Calls visit(row) for every row of a table (a std::tuple of rows), in order.
template <class Table, class Visit>
constexpr void for_each_parameter(const Table& table, Visit&& visit) {
  std::apply([&](const auto&... row) { (visit(row), ...); }, table);
}

// The number of fields of an aggregate: what Boost.PFR's tuple_size gives (Debian 12's default Boost, 1.74, predates
// PFR, and libboost1.81-dev would replace it for every build on the machine). T{f, f, ...} with one more `f` that
// converts to any field type until the braces no longer initialize T.
namespace detail {
struct AnyField {
  template <class T>
  constexpr operator T&() const noexcept {  // only named in unevaluated requires-expressions
    return *static_cast<T*>(nullptr);
  }
};
}  // namespace detail
template <class T, class... Fields>
consteval std::size_t field_count() {
  if constexpr (requires { T{Fields{}..., detail::AnyField{}}; }) {
    return field_count<T, Fields..., detail::AnyField>();
  } else {
    return sizeof...(Fields);
  }
}

namespace detail {
// A number's value, or an optional quantity's when given.
template <class Value>
std::optional<double> given_value(const Value& value) {
  return static_cast<double>(value);
}
inline std::optional<double> given_value(const std::optional<double>& value) { return value; }
}  // namespace detail

// " Pa" for a quantity row, "" for a pure number: what follows an SI value of the row in a message.
template <class Row>
std::string si_unit_suffix(const Row& row) {
  if (row.dimension == units::Dimension::Dimensionless) return "";
  return fmt::format(" {}", units::si_symbol(row.dimension));
}

// Throws InvalidInput "WHAT KEY = VALUE UNIT: expected RANGE UNIT" for the first number of `options` outside its
// row's range, in SI ("puncture critical_pressure = -1 Pa: expected > 0 Pa"; an optional quantity not given is not
// checked).
template <class Options, class Table>
void check_ranges(const Table& table, const Options& options, std::string_view what) {
  for_each_parameter(table, [&](const auto& row) {
    if constexpr (requires { row.accepts(0.0); }) {
      const std::optional<double> value = detail::given_value(options.*row.field);
      if (value && !row.accepts(*value)) {
        const std::string unit = si_unit_suffix(row);
        throw InvalidInput(
            fmt::format("{} {} = {:g}{}: expected {}{}", what, row.attribute(), *value, unit, row.range(), unit));
      }
    }
  });
}

}  // namespace needlekit
