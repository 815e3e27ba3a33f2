#include "needlekit/uncertainty/design_outcome.hpp"

#include <cmath>

#include "needlekit/analysis/bending.hpp"
#include "needlekit/analysis/skin_permeation.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/needle/section_properties.hpp"

namespace needlekit::uncertainty {
namespace {

materials::NeedleMaterial material_of(const DesignValues& v) {
  materials::NeedleMaterial material;
  material.youngs_modulus = v.youngs_modulus;
  material.yield_strength = v.yield_strength;
  material.allowable_stress = v.allowable_stress;
  return material;
}

bool valid_values(const DesignValues& v) {
  try {
    needle::validate(v.needle, "needle");
    analysis::validate(v.tissue, "tissue");
  } catch (const InvalidInput&) {
    return false;
  }
  const auto positive = [](const std::optional<double>& x) { return !x || (std::isfinite(*x) && *x > 0); };
  return std::isfinite(v.youngs_modulus) && v.youngs_modulus > 0 && positive(v.yield_strength) &&
         positive(v.allowable_stress) && std::isfinite(v.width) && v.width > 0 && v.angle >= 0 &&
         v.angle < M_PI / 2 && std::isfinite(v.target_depth) && v.target_depth > 0;
}

}  // namespace

DesignOutcomeEvaluator::DesignOutcomeEvaluator(const DesignCase& nominal)
    : nominal_(design_values(nominal)), options_(nominal.options) {
  analysis::performance_index(nominal.design, nominal.conditions, nominal.options);  // validates the nominal case
  const needle::NeedleGeometry& n = nominal_.needle;
  tip_area_ = needle::tip_area(n);
  base_section_ = needle::section_at(n, n.length);
  const double i2 = base_section_.second_moment_min;
  if (n.shape != needle::Shape::Cylinder) {
    const materials::NeedleMaterial material = material_of(nominal_);
    tapered_factor_ = analysis::critical_buckling_load(n, material, options_.buckling).critical_load * n.length *
                      n.length / (material.youngs_modulus * i2);
  }
  bending_factor_ = analysis::critical_bending_load(n, 1.0) * n.length;
}

bool DesignOutcomeEvaluator::nominal_section(const needle::NeedleGeometry& n) const {
  return n.tip_diameter == nominal_.needle.tip_diameter && n.base_diameter == nominal_.needle.base_diameter &&
         n.bore_diameter == nominal_.needle.bore_diameter;
}

double DesignOutcomeEvaluator::critical_buckling_load(const DesignValues& v) const {
  const needle::NeedleGeometry& n = v.needle;
  const double e = v.youngs_modulus;
  const bool nominal = nominal_section(n);
  // The base section depends on the diameters only (at s = L the bevel is the full circle).
  const needle::SectionProperties base = nominal ? base_section_ : needle::section_at(n, n.length);
  if (n.shape == needle::Shape::Cylinder) {  // as analysis::critical_buckling_load(): Euler, or Johnson if short
    const double k = analysis::effective_length_factor(options_.buckling.end_condition, options_.buckling.effective_length);
    const double slenderness = k * n.length / std::sqrt(base.second_moment_min / base.area);  // Eq 2.33
    if (options_.buckling.johnson_for_short_columns && v.yield_strength &&
        slenderness < analysis::column_constant(e, *v.yield_strength)) {
      return analysis::johnson_critical_load(base.area, *v.yield_strength, e, slenderness);  // Eq 2.35
    }
    return analysis::euler_critical_load(e, base.second_moment_min, n.length, k);  // Eq 2.28
  }
  if (nominal) return tapered_factor_ * e * base.second_moment_min / (n.length * n.length);  // Eq 2.36
  return analysis::critical_buckling_load(n, material_of(v), options_.buckling).critical_load;
}

bool DesignOutcomeEvaluator::buckles(const DesignValues& v, double demand) const {
  const needle::NeedleGeometry& n = v.needle;
  if (n.shape == needle::Shape::Cylinder || nominal_section(n) ||
      options_.buckling.end_condition != analysis::EndCondition::FixedFree) {
    return !(demand < critical_buckling_load(v));
  }
  // A new tapered section, fixed-free: P_cr = m·E·I2/L² with π²/4·I_tip/I2 <= m <= π²/4 (the column lies between
  // uniform columns of its weakest and strongest sections; Sturm comparison, as in DesignPointEvaluator), so most
  // samples need no eigenvalue.
  const double i2 = needle::section_at(n, n.length).second_moment_min;
  const double scale = v.youngs_modulus * i2 / (n.length * n.length);
  const double m_max = M_PI * M_PI / 4;
  if (demand >= m_max * scale) return true;
  if (demand < m_max * (needle::section_at(n, 0.0).second_moment_min / i2) * scale) return false;
  return !(demand < critical_buckling_load(v));
}

double DesignOutcomeEvaluator::critical_bending_load(const DesignValues& v) const {
  if (nominal_section(v.needle)) return bending_factor_ * *v.allowable_stress / v.needle.length;
  return analysis::critical_bending_load(v.needle, *v.allowable_stress);
}

DesignOutcome DesignOutcomeEvaluator::operator()(const DesignValues& v) const {
  DesignOutcome r;
  if (!valid_values(v)) {
    r.valid = false;
    return r;
  }
  const needle::NeedleGeometry& n = v.needle;
  const double area = nominal_section(n) ? tip_area_ : needle::tip_area(n);
  const double force = analysis::puncture_force(area, v.tissue);                        // Eq 4.2
  const double d = analysis::skin_deformation(area, v.tissue).depth;                    // Eq 4.3
  const double h = analysis::cutting_depth(n.length, d);                                // Eq 4.4
  r.punctures = std::isfinite(force) && std::abs(force) > 0 && h > 0;
  r.spacing_ok = !(options_.spacing_factor > 0 &&
                   v.width < options_.spacing_factor * v.needles_per_row * n.base_diameter * (1 - 1e-12));
  const double permeation = analysis::ideal_permeation_depth(n.hollow(), n.length, d, v.target_depth);  // Eq 4.23
  r.reaches_target = permeation > 0;
  const double buckling_force = analysis::angled_buckling_force(force, v.angle);       // Eq 5.3
  r.buckles = buckles(v, options_.buckling_safety_factor * buckling_force);  // Eq 4.5
  const double bending_force = analysis::angled_bending_force(force, v.angle);         // Eq 5.4
  if (v.allowable_stress) {
    r.bends = !(options_.bending_safety_factor * bending_force < critical_bending_load(v));
  } else if (!(bending_force > 0)) {
    r.bends = false;
  }
  if (r.spacing_ok && r.reaches_target && !r.buckles && r.bends != true) {
    const double pitch = options_.index_pitch.value_or(v.width / v.needles_per_row);
    r.performance_index = analysis::permeation_factor(n, std::max(0.0, h)) / (pitch * pitch * permeation);  // Eq 4.25
  }
  return r;
}

}  // namespace needlekit::uncertainty
