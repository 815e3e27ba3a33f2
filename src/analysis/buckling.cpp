#include "needlekit/analysis/buckling.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/needle/section_properties.hpp"

namespace needlekit::analysis {

double effective_length_factor(EndCondition end, EffectiveLengthValue value) {
  const bool theory = value == EffectiveLengthValue::Theoretical;
  switch (end) {  // §2.5 [Mott 2008]
    case EndCondition::FixedFree: return theory ? 2.0 : 2.1;
    case EndCondition::FixedPinned: return theory ? 0.7 : 0.8;
    case EndCondition::FixedFixed: return theory ? 0.5 : 0.65;
  }
  return 2.0;
}

double euler_critical_load(double e, double i, double length, double k) {
  const double le = k * length;
  return M_PI * M_PI * e * i / (le * le);  // Eq 2.28
}

double column_constant(double e, double yield_strength) {
  return std::sqrt(2 * M_PI * M_PI * e / yield_strength);  // Eq 2.34
}

double johnson_critical_load(double area, double sy, double e, double slenderness) {
  return area * sy * (1 - sy * slenderness * slenderness / (4 * M_PI * M_PI * e));  // Eq 2.35
}

double tapered_column_factor(const needle::NeedleGeometry& n, EndCondition end_condition) {
  needle::NeedleGeometry unit = n;  // the same section along s/L on a column of length 1
  unit.length = 1;
  const double i2 = needle::section_at(unit, 1.0).second_moment_min;
  ColumnEigenvalueOptions eigen;
  eigen.end_condition = end_condition;
  // Eq 2.36: P = m·E·I2/L², so m is the load of the column with EI(s)/(E·I2) and L = 1.
  return column_buckling_load([&](double s) { return needle::section_at(unit, s).second_moment_min / i2; }, 1.0,
                              eigen);
}

std::string_view to_string(EndCondition end_condition) { return name_of(kEndConditionNames, end_condition); }

std::string_view to_string(EffectiveLengthValue value) { return name_of(kEffectiveLengthNames, value); }

std::string_view to_string(BucklingMethod method) { return name_of(kBucklingMethodNames, method); }

BucklingResult critical_buckling_load(const needle::NeedleGeometry& n, const materials::NeedleMaterial& material,
                                      const BucklingOptions& options, std::optional<double> known_tapered_factor) {
  needle::validate(n);
  materials::validate(material);
  const double e = material.youngs_modulus;
  const needle::SectionProperties base = needle::section_at(n, n.length);
  const double k = effective_length_factor(options.end_condition, options.effective_length);
  BucklingResult r;
  r.end_condition = options.end_condition;
  r.effective_length_factor = k;
  r.slenderness_ratio = k * n.length / std::sqrt(base.second_moment_min / base.area);  // Eq 2.33
  if (material.yield_strength) {
    r.column_constant = column_constant(e, *material.yield_strength);
  } else if (options.explain) {
    r.note = "C_c not assessed: the material has no yield_strength";
  }
  if (n.shape == needle::Shape::Cylinder) {
    // Table 4.1: P = 0.25·E·π³(D2⁴ − D3⁴)/(64L²) for K = 2, i.e. Eq 2.28 with I = π(D2⁴ − D3⁴)/64.
    r.method = BucklingMethod::Euler;
    r.critical_load = euler_critical_load(e, base.second_moment_min, n.length, k);
    if (options.johnson_for_short_columns && material.yield_strength && r.slenderness_ratio < r.column_constant) {
      r.method = BucklingMethod::Johnson;
      r.critical_load = johnson_critical_load(base.area, *material.yield_strength, e, r.slenderness_ratio);
      if (options.explain) {
        r.note = fmt::format("short column (L_e/r = {:.3g} < C_c = {:.3g}): J. B. Johnson formula (Eq 2.35)",
                             r.slenderness_ratio, r.column_constant);
      }
    }
    r.tapered_factor = r.critical_load * n.length * n.length / (e * base.second_moment_min);
    return r;
  }
  // Cones and bevels: the varying-section column (Eq 2.36 with m computed). The exact end conditions are used; the
  // practical K values apply to the uniform-column formula only. For the bevel, the smaller principal second moment
  // of each section is used and the eccentricity of its shifting centroid is neglected (docs/bevel-buckling.md).
  r.method = BucklingMethod::TaperedEigenvalue;
  r.tapered_factor = known_tapered_factor ? *known_tapered_factor : tapered_column_factor(n, options.end_condition);
  // The grouping is DesignPointEvaluator::needle_buckles()'s, so that both decide φ on the same bits.
  r.critical_load = r.tapered_factor * (e * base.second_moment_min / (n.length * n.length));
  return r;
}

}  // namespace needlekit::analysis
