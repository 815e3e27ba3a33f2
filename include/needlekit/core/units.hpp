// Physical quantities at the edges of needlekit: parsing "230 um", "169 GPa", "0.05 mJ", "30 deg", "6.25 /mm" into
// SI values, and formatting SI values back with a unit. Inside the library every quantity is SI, with no suffix.
#pragma once
#include <string>
#include <string_view>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::units {

enum class Dimension {
  Dimensionless,  // a pure number, e.g. a Poisson ratio or a count
  Length,         // m
  Area,           // m^2
  Volume,         // m^3
  Force,          // N
  Pressure,       // Pa (also Young's modulus, stress)
  Energy,         // J
  Angle,          // rad
  InverseLength,  // 1/m (the tissue's exponential constant tau)
  Stiffness,      // N/m (spring constants)
  ForcePerArea,   // N/m^2 per unit area slope (the same dimension as Pressure, kept for clarity of messages)
};

// The names of the dimensions, as error messages write them ("length", "pressure (or modulus, stress)").
inline constexpr EnumTable<Dimension, 11> kDimensionNames{{
    {Dimension::Dimensionless, "dimensionless number", "a pure number, e.g. a Poisson ratio or a count"},
    {Dimension::Length, "length", "SI unit m"},
    {Dimension::Area, "area", "SI unit m^2"},
    {Dimension::Volume, "volume", "SI unit m^3"},
    {Dimension::Force, "force", "SI unit N"},
    {Dimension::Pressure, "pressure (or modulus, stress)", "SI unit Pa (also Young's modulus, stress)"},
    {Dimension::Energy, "energy", "SI unit J"},
    {Dimension::Angle, "angle", "SI unit rad"},
    {Dimension::InverseLength, "inverse length", "SI unit 1/m (the tissue's exponential constant tau)"},
    {Dimension::Stiffness, "stiffness (force per length)", "SI unit N/m (spring constants)"},
    {Dimension::ForcePerArea, "force per area", "SI unit N/m^2 (the slope of a force per unit area)"},
}};

// The SI unit symbol of a dimension ("m", "Pa", ...): a unit, not a name (Pressure and ForcePerArea share "Pa").
std::string_view si_symbol(Dimension dimension);
// A human name of a dimension ("length", "pressure", ...), for error messages: its name in kDimensionNames.
std::string_view dimension_name(Dimension dimension);

// Parses "<number> <unit>" (the space is optional) into SI. Accepted units include nm um µm mm cm m; um2 mm2 m2
// (also um^2); um3 mm3 m3; uN mN N kN; Pa kPa MPa GPa psi; nJ uJ mJ J; deg rad; /um /mm /m (also 1/mm); N/m N/mm.
// A bare number is accepted only for Dimension::Dimensionless. Throws InvalidInput naming `what` (a key or
// option name) with the offending text and the expected dimension.
double parse_quantity(std::string_view text, Dimension expected, std::string_view what);

// The factor that converts a value in `unit` to SI, or throws InvalidInput if `unit` is unknown or of another
// dimension. Used for surface-mesh units ("mm") and table headers.
double unit_factor(std::string_view unit, Dimension expected, std::string_view what);

// `value` (in a unit of the given factor, e.g. 1e-6 for um) in SI, correctly rounded for decimal units: "200 um"
// becomes the double nearest to 2e-4 m (parse_quantity uses it).
double to_si(double value, double factor);

// `value` rounded to 12 significant digits. The output conversions use it, so that a value the user gave comes back
// as given (200 um, not 199.99999999999997 um) and a decimal sweep lands on the decimal values.
double round_to_12_digits(double value);

// Formats an SI value in the given unit, e.g. format(2.3e-4, "um") == "230 um".
std::string format(double value_si, std::string_view unit, int significant_digits = 6);

}  // namespace needlekit::units
