// Critical buckling load of a needle (dissertation §2.5, §4.3, Table 4.1, Eqs 2.26–2.36, 5.5, 5.6).
#pragma once
#include <optional>
#include <string>

#include "needlekit/analysis/column_eigenvalue.hpp"
#include "needlekit/core/enum_table.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::analysis {

enum class EffectiveLengthValue {
  Theoretical,  // K = 2.0 (fixed-free), 0.7 (fixed-pinned), 0.5 (fixed-fixed)  [Mott 2008]
  Practical,    // K = 2.1, 0.8, 0.65
};
inline constexpr EnumTable<EffectiveLengthValue, 2> kEffectiveLengthNames{{
    {EffectiveLengthValue::Theoretical, "theoretical", "K = 2.0, 0.7, 0.5 (fixed-free, fixed-pinned, fixed-fixed)"},
    {EffectiveLengthValue::Practical, "practical", "K = 2.1, 0.8, 0.65 (Mott 2008's recommended values)"},
}};

// The names of [insertion] end_condition and effective_length ("fixed-free", "theoretical", ...).
std::string_view to_string(EndCondition end_condition);
std::string_view to_string(EffectiveLengthValue value);

// End-fixity factor K, L_e = K·L (§2.5).
double effective_length_factor(EndCondition end_condition, EffectiveLengthValue value);

// Eq 2.28: P_cr = π²·E·I / (K·L)².
double euler_critical_load(double youngs_modulus, double second_moment, double length, double effective_length_factor);

// Eq 2.34: C_c = √(2π²E / s_y).
double column_constant(double youngs_modulus, double yield_strength);

// Eq 2.35 (J. B. Johnson): P_cr = A·s_y·[1 − s_y·(L_e/r)² / (4π²E)].
double johnson_critical_load(double area, double yield_strength, double youngs_modulus, double slenderness_ratio);

// Eq 2.36 / Table 4.1: the factor m of P_cr = m·E·I2/L² for a column with the needle's own profile (π²/4 for a
// uniform fixed-free column). I2 is the base section's second moment (π(D2⁴ − D3⁴)/64 for round sections). m is
// dimensionless and depends only on how the section varies along s/L, so it is computed as the lowest eigenvalue of
// column_buckling_load() for the column scaled to unit length and unit base rigidity: one section (shape, D1, D2, D3)
// gives the same m to the last bit for every L and E, which is what lets the optimizer and evaluate_many memoize it.
double tapered_column_factor(const needle::NeedleGeometry& needle, EndCondition end_condition = EndCondition::FixedFree);

enum class BucklingMethod {
  Euler,                  // uniform column, Eq 2.28 (Table 4.1 for cylinders)
  Johnson,                // uniform short column, Eq 2.35 (slenderness below C_c)
  TaperedEigenvalue,      // cone or bevel: eigenvalue of the varying-section column (Eq 2.36 with computed m)
};
inline constexpr EnumTable<BucklingMethod, 3> kBucklingMethodNames{{
    {BucklingMethod::Euler, "euler", "uniform column, Eq 2.28 (Table 4.1 for cylinders)"},
    {BucklingMethod::Johnson, "johnson", "uniform short column, Eq 2.35 (slenderness below C_c)"},
    {BucklingMethod::TaperedEigenvalue, "tapered_eigenvalue",
     "cone or bevel: eigenvalue of the varying-section column (Eq 2.36)"},
}};
std::string_view to_string(BucklingMethod method);

struct BucklingOptions {
  EndCondition end_condition = EndCondition::FixedFree;
  EffectiveLengthValue effective_length = EffectiveLengthValue::Theoretical;
  // Use the Johnson formula when a cylinder's slenderness L_e/r is below C_c and the material has a yield strength.
  // The dissertation's Table 4.1 uses Euler only (set false to reproduce it exactly; Table 6.3 is unaffected).
  bool johnson_for_short_columns = true;
  // false: BucklingResult::note is left empty (the numbers are the same; saves formatting it)
  bool explain = true;
};

struct BucklingResult {
  double critical_load = 0;        // N
  BucklingMethod method = BucklingMethod::Euler;
  EndCondition end_condition = EndCondition::FixedFree;  // the end condition it was computed for
  double effective_length_factor = 2.0;                  // K of L_e = K·L
  double tapered_factor = 0;       // m of Eq 2.36 (for cones and bevels; π²/4·(4/K²) equivalents are not used)
  double slenderness_ratio = 0;    // L_e / r with r = √(I_min/A) of the base section
  double column_constant = 0;      // C_c, 0 when the material has no yield strength
  std::string note;                // e.g. "short column: Johnson formula", "C_c not assessed: no yield strength"
};

// Cylinders: Euler (or Johnson for short columns). Cones and bevels: the varying-section eigenvalue with the bevel's
// smaller principal second moment at each section (section_at()); the method is documented in docs/bevel-buckling.md.
// `known_tapered_factor`: m of this needle's section (tapered_column_factor(needle, options.end_condition)) when the
// caller has it memoized; the result is then the same to the last bit as without it.
BucklingResult critical_buckling_load(const needle::NeedleGeometry& needle, const materials::NeedleMaterial& material,
                                      const BucklingOptions& options = {},
                                      std::optional<double> known_tapered_factor = std::nullopt);

}  // namespace needlekit::analysis
