// The force needed to puncture the tissue as a function of the needle's tip (dissertation Eq 4.2 and laws beyond
// it). Every law is a function of the tip area A; the diameter laws read the tip's equivalent diameter
// D = √(4A/π) (= D1 for cylinders and cones). Each law carries the range of tips it was measured on; outside it the
// force is an extrapolation and the caller says so (puncture_force_validity_note).
#pragma once
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::analysis {

enum class PunctureForceLawKind {
  Eq4_2,           // F = 0.00019·A − 0.66 (A in µm², F in N): dissertation Eq 4.2, from Davis et al. 2004
  Romgens2014,     // F linear in the tip diameter, ~20 mN at 5 µm to ~167 mN at 37 µm: Römgens et al. 2014
  LinearArea,      // F = slope·A + intercept, user coefficients
  LinearDiameter,  // F = slope·D + intercept, user coefficients
  Table,           // F(D) interpolated linearly in a user table of tip diameters and forces
};

// The one table of the laws' names, as files, help and JSON write them, with a one-line meaning.
inline constexpr EnumTable<PunctureForceLawKind, 5> kPunctureForceLawKindNames{{
    {PunctureForceLawKind::Eq4_2, "eq-4.2", "F = 0.00019 N/um2 * A - 0.66 N (linear in the tip area)"},
    {PunctureForceLawKind::Romgens2014, "romgens-2014",
     "F linear in the tip diameter: 20 mN at 5 um to 167 mN at 37 um"},
    {PunctureForceLawKind::LinearArea, "linear-area", "F = slope * A + intercept (user coefficients)"},
    {PunctureForceLawKind::LinearDiameter, "linear-diameter", "F = slope * D + intercept (user coefficients)"},
    {PunctureForceLawKind::Table, "table", "F(D) interpolated linearly in a table of tip diameters and forces"},
}};
std::string_view to_string(PunctureForceLawKind kind);
// Where the law comes from: the publication it was measured in, or "user" for the laws of user coefficients.
std::string_view puncture_force_law_source(PunctureForceLawKind kind);
// Throws InvalidInput naming `what` and listing the accepted names.
PunctureForceLawKind puncture_force_law_from_string(std::string_view name, std::string_view what);
// "eq-4.2, romgens-2014, ..." for messages and help.
std::string puncture_force_law_names();

struct PunctureForceLaw {
  PunctureForceLawKind kind = PunctureForceLawKind::Eq4_2;
  // Coefficients of the linear laws: slope in N/m² (area laws) or N/m (diameter laws), intercept in N.
  double slope = 1.9e8;      // Eq 4.2: 0.00019 N/µm²
  double intercept = -0.66;  // N
  // Table law: tip diameters (m, strictly increasing, >= 2 entries) and the puncture forces there (N).
  std::vector<double> table_tip_diameter;
  std::vector<double> table_force;
  // Tips the law was measured on, as equivalent tip diameters (m); 0 / empty: unbounded.
  double valid_min_tip_diameter = 0;
  std::optional<double> valid_max_tip_diameter;
};

// The presets with their published coefficients and validity ranges (kind Eq4_2 or Romgens2014).
PunctureForceLaw eq_4_2_puncture_force_law();
PunctureForceLaw romgens_2014_puncture_force_law();
// The law of `kind` with the preset's coefficients (LinearArea/LinearDiameter/Table: zero coefficients, to be filled).
PunctureForceLaw puncture_force_law_preset(PunctureForceLawKind kind);

// Throws InvalidInput naming `where` for non-finite coefficients, a bad table or an empty validity range.
void validate(const PunctureForceLaw& law, std::string_view where);

// D = √(4A/π).
double equivalent_tip_diameter(double tip_area);

// The law's puncture force (signed: Eq 4.2 is negative for A < 3473.7 µm²).
double puncture_force(double tip_area, const PunctureForceLaw& law);

// Empty when the tip lies within the law's validity range and the force is positive; otherwise why the value is an
// extrapolation, e.g. "puncture force law eq-4.2 used outside its validity range ...".
std::optional<std::string> puncture_force_validity_note(double tip_area, const PunctureForceLaw& law);

}  // namespace needlekit::analysis
