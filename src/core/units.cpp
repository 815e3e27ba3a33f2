#include "needlekit/core/units.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::units {
namespace {

struct UnitEntry {
  std::string_view symbol;
  Dimension dimension;
  double factor;  // multiply a value in this unit by factor to get SI
};

constexpr double kPsi = 6894.757293168361;  // Pa per psi (NIST SP 811)

// One table of every accepted unit; aliases are separate rows.
constexpr std::array kUnits{
    UnitEntry{"nm", Dimension::Length, 1e-9},        UnitEntry{"um", Dimension::Length, 1e-6},
    UnitEntry{"µm", Dimension::Length, 1e-6},        UnitEntry{"mm", Dimension::Length, 1e-3},
    UnitEntry{"cm", Dimension::Length, 1e-2},        UnitEntry{"m", Dimension::Length, 1.0},
    UnitEntry{"um2", Dimension::Area, 1e-12},        UnitEntry{"um^2", Dimension::Area, 1e-12},
    UnitEntry{"µm2", Dimension::Area, 1e-12},        UnitEntry{"µm^2", Dimension::Area, 1e-12},
    UnitEntry{"mm2", Dimension::Area, 1e-6},         UnitEntry{"mm^2", Dimension::Area, 1e-6},
    UnitEntry{"m2", Dimension::Area, 1.0},           UnitEntry{"m^2", Dimension::Area, 1.0},
    UnitEntry{"um3", Dimension::Volume, 1e-18},      UnitEntry{"um^3", Dimension::Volume, 1e-18},
    UnitEntry{"mm3", Dimension::Volume, 1e-9},       UnitEntry{"mm^3", Dimension::Volume, 1e-9},
    UnitEntry{"m3", Dimension::Volume, 1.0},         UnitEntry{"m^3", Dimension::Volume, 1.0},
    UnitEntry{"uN", Dimension::Force, 1e-6},         UnitEntry{"mN", Dimension::Force, 1e-3},
    UnitEntry{"N", Dimension::Force, 1.0},           UnitEntry{"kN", Dimension::Force, 1e3},
    UnitEntry{"Pa", Dimension::Pressure, 1.0},       UnitEntry{"kPa", Dimension::Pressure, 1e3},
    UnitEntry{"MPa", Dimension::Pressure, 1e6},      UnitEntry{"GPa", Dimension::Pressure, 1e9},
    UnitEntry{"psi", Dimension::Pressure, kPsi},     UnitEntry{"N/m2", Dimension::Pressure, 1.0},
    UnitEntry{"N/mm2", Dimension::Pressure, 1e6},    UnitEntry{"N/um2", Dimension::Pressure, 1e12},
    UnitEntry{"nJ", Dimension::Energy, 1e-9},        UnitEntry{"uJ", Dimension::Energy, 1e-6},
    UnitEntry{"mJ", Dimension::Energy, 1e-3},        UnitEntry{"J", Dimension::Energy, 1.0},
    UnitEntry{"deg", Dimension::Angle, M_PI / 180},  UnitEntry{"rad", Dimension::Angle, 1.0},
    UnitEntry{"/um", Dimension::InverseLength, 1e6}, UnitEntry{"1/um", Dimension::InverseLength, 1e6},
    UnitEntry{"/mm", Dimension::InverseLength, 1e3}, UnitEntry{"1/mm", Dimension::InverseLength, 1e3},
    UnitEntry{"/m", Dimension::InverseLength, 1.0},  UnitEntry{"1/m", Dimension::InverseLength, 1.0},
    UnitEntry{"N/m", Dimension::Stiffness, 1.0},     UnitEntry{"N/mm", Dimension::Stiffness, 1e3},
    UnitEntry{"N/um", Dimension::Stiffness, 1e6},    UnitEntry{"mN/mm", Dimension::Stiffness, 1.0},
    // Energy per area (fracture toughness) has the dimension of force per length.
    UnitEntry{"J/m2", Dimension::Stiffness, 1.0},    UnitEntry{"J/m^2", Dimension::Stiffness, 1.0},
    UnitEntry{"kJ/m2", Dimension::Stiffness, 1e3},   UnitEntry{"kJ/m^2", Dimension::Stiffness, 1e3},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool same_dimension(Dimension a, Dimension b) {
  auto canonical = [](Dimension d) { return d == Dimension::ForcePerArea ? Dimension::Pressure : d; };
  return canonical(a) == canonical(b);
}

std::string examples_of(Dimension d) {
  std::string out;
  for (const auto& u : kUnits) {
    if (same_dimension(u.dimension, d)) {
      if (!out.empty()) out += ", ";
      out += u.symbol;
    }
  }
  return out;
}

}  // namespace

std::string_view si_symbol(Dimension d) {
  switch (d) {
    case Dimension::Dimensionless: return "";
    case Dimension::Length: return "m";
    case Dimension::Area: return "m^2";
    case Dimension::Volume: return "m^3";
    case Dimension::Force: return "N";
    case Dimension::Pressure:
    case Dimension::ForcePerArea: return "Pa";
    case Dimension::Energy: return "J";
    case Dimension::Angle: return "rad";
    case Dimension::InverseLength: return "1/m";
    case Dimension::Stiffness: return "N/m";
  }
  return "";
}

std::string_view dimension_name(Dimension d) { return name_of(kDimensionNames, d); }

double unit_factor(std::string_view unit, Dimension expected, std::string_view what) {
  unit = trim(unit);
  for (const auto& u : kUnits) {
    if (u.symbol == unit) {
      if (!same_dimension(u.dimension, expected)) {
        throw InvalidInput(fmt::format("{}: unit '{}' is a {}, expected a {} (units: {})", what, unit,
                                       dimension_name(u.dimension), dimension_name(expected),
                                       examples_of(expected)));
      }
      return u.factor;
    }
  }
  throw InvalidInput(fmt::format("{}: unknown unit '{}', expected a {} unit ({})", what, unit,
                                 dimension_name(expected), examples_of(expected)));
}

double parse_quantity(std::string_view text, Dimension expected, std::string_view what) {
  const std::string_view t = trim(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec != std::errc() || end == t.data()) {
    throw InvalidInput(fmt::format("{}: '{}' is not a quantity, expected a number{} ({})", what, text,
                                   expected == Dimension::Dimensionless ? "" : " followed by a unit",
                                   expected == Dimension::Dimensionless ? "dimensionless" : examples_of(expected)));
  }
  if (!std::isfinite(value)) {
    throw InvalidInput(fmt::format("{}: '{}' is not a finite number", what, text));
  }
  const std::string_view unit = trim(std::string_view(end, static_cast<size_t>(t.data() + t.size() - end)));
  if (unit.empty()) {
    if (expected == Dimension::Dimensionless) return value;
    throw InvalidInput(fmt::format("{}: '{}' has no unit; a {} needs one ({})", what, text,
                                   dimension_name(expected), examples_of(expected)));
  }
  if (expected == Dimension::Dimensionless) {
    throw InvalidInput(fmt::format("{}: '{}' carries a unit but a dimensionless number is expected", what, text));
  }
  return to_si(value, unit_factor(unit, expected, what));
}

double to_si(double value, double factor) {
  // A decimal submultiple (um = 1e-6 m) divides by its exactly representable inverse: 200 / 1e6 is the double
  // nearest to 0.0002, which prints back as 200 um; 200 * 1e-6 is 1 ulp below it (199.99999999999997 um).
  const double inverse = std::round(1.0 / factor);
  if (factor < 1 && inverse <= 1e15 && inverse * factor == 1.0) return value / inverse;
  return value * factor;
}

double round_to_12_digits(double value) {
  if (!std::isfinite(value) || value == 0) return value;
  const std::string text = fmt::format("{:.12g}", value);
  double rounded = value;
  std::from_chars(text.data(), text.data() + text.size(), rounded);
  return rounded;
}

std::string format(double value_si, std::string_view unit, int significant_digits) {
  double factor = 1.0;
  for (const auto& u : kUnits) {
    if (u.symbol == unit) {
      factor = u.factor;
      break;
    }
  }
  return fmt::format("{:.{}g} {}", value_si / factor, significant_digits, unit);
}

}  // namespace needlekit::units
