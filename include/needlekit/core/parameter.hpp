// One declaration per parameter (FEBio's parameter lists are the model): the key it has in files, the field of the
// Options struct it sets (whose initializer is the default: declared there, nowhere else), its valid range and a
// one-line meaning. The config readers, their range checks and the CLI help all read the declaration.
//
//   inline constexpr Parameter<fem::SolverOptions, double> kResidualTolerance{
//       "residual_tolerance", &fem::SolverOptions::residual_tolerance, 0, 1, Bound::Open, Bound::Open, "..."};
#pragma once
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>
#include <string_view>

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

  // The default: the field's initializer in Options.
  Value default_value() const { return Options{}.*field; }

  bool accepts(double value) const {
    if (!std::isfinite(value)) return false;
    const bool above = min_bound == Bound::Open ? value > min : value >= min;
    const bool below = max_bound == Bound::Open ? value < max : value <= max;
    return above && below;
  }

  // "in (0, 1)", ">= 1", "> 0".
  std::string range() const {
    const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
    if (has_min && has_max) {
      return fmt::format("in {}{:g}, {:g}{}", min_bound == Bound::Open ? '(' : '[', min, max,
                         max_bound == Bound::Open ? ')' : ']');
    }
    if (has_min) return fmt::format("{} {:g}", min_bound == Bound::Open ? ">" : ">=", min);
    if (has_max) return fmt::format("{} {:g}", max_bound == Bound::Open ? "<" : "<=", max);
    return "any";
  }
};

}  // namespace needlekit
