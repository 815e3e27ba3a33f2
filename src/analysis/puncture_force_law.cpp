#include "needlekit/analysis/puncture_force_law.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {
namespace {

constexpr double kPi = 3.14159265358979323846;


bool diameter_law(PunctureForceLawKind kind) {
  return kind == PunctureForceLawKind::Romgens2014 || kind == PunctureForceLawKind::LinearDiameter;
}

std::string um(double metres) { return fmt::format("{:.4g} um", metres * 1e6); }

}  // namespace

std::string_view to_string(PunctureForceLawKind kind) { return name_of(kPunctureForceLawKindNames, kind); }

std::string_view puncture_force_law_source(PunctureForceLawKind kind) {
  switch (kind) {
    case PunctureForceLawKind::Eq4_2:
      return "dissertation Eq 4.2 / 5.1, after Davis et al. 2004, J Biomech 37:1155 (insertion forces of ~0.1-3 N: "
             "tip areas 4000-19300 um2, equivalent tip diameters 71-157 um)";
    case PunctureForceLawKind::Romgens2014:
      return "Romgens et al. 2014, J Mech Behav Biomed Mater 40:397 (single microneedles in ex vivo human skin, tip "
             "diameters 5-37 um)";
    case PunctureForceLawKind::LinearArea:
    case PunctureForceLawKind::LinearDiameter:
    case PunctureForceLawKind::Table: break;
  }
  return "user";
}

std::string puncture_force_law_names() {
  std::string names;
  for (const auto& law : kPunctureForceLawKindNames) {
    names += fmt::format("{}\"{}\"", names.empty() ? "" : ", ", law.name);
  }
  return names;
}

PunctureForceLawKind puncture_force_law_from_string(std::string_view name, std::string_view what) {
  for (const auto& law : kPunctureForceLawKindNames)
    if (law.name == name) return law.value;
  throw InvalidInput(fmt::format("{}: unknown puncture force law '{}', expected one of: {}", what, name,
                                 puncture_force_law_names()));
}

PunctureForceLaw eq_4_2_puncture_force_law() {
  PunctureForceLaw law;  // the defaults are Eq 4.2's coefficients
  // Davis et al. 2004 measured forces of about 0.1 to 3 N: A = (F + 0.66 N) / 0.00019 N/um2 from 4000 to 19263 um2.
  law.valid_min_tip_diameter = equivalent_tip_diameter((0.1 + 0.66) / 1.9e8);
  law.valid_max_tip_diameter = equivalent_tip_diameter((3.0 + 0.66) / 1.9e8);
  return law;
}

PunctureForceLaw romgens_2014_puncture_force_law() {
  PunctureForceLaw law;
  law.kind = PunctureForceLawKind::Romgens2014;
  // The line through (5 um, 20 mN) and (37 um, 167 mN): slope 4593.75 N/m, intercept -2.97 mN.
  law.slope = (0.167 - 0.020) / (37e-6 - 5e-6);
  law.intercept = 0.020 - law.slope * 5e-6;
  law.valid_min_tip_diameter = 5e-6;
  law.valid_max_tip_diameter = 37e-6;
  return law;
}

PunctureForceLaw puncture_force_law_preset(PunctureForceLawKind kind) {
  switch (kind) {
    case PunctureForceLawKind::Eq4_2: return eq_4_2_puncture_force_law();
    case PunctureForceLawKind::Romgens2014: return romgens_2014_puncture_force_law();
    default: break;
  }
  PunctureForceLaw law;
  law.kind = kind;
  law.slope = 0;
  law.intercept = 0;
  return law;
}

void validate(const PunctureForceLaw& law, std::string_view where) {
  if (!std::isfinite(law.slope)) throw InvalidInput(fmt::format("{}.slope: {} is not finite", where, law.slope));
  if (!std::isfinite(law.intercept)) {
    throw InvalidInput(fmt::format("{}.intercept: {} N is not finite", where, law.intercept));
  }
  if (law.kind == PunctureForceLawKind::Table) {
    const auto& d = law.table_tip_diameter;
    if (d.size() < 2 || d.size() != law.table_force.size()) {
      throw InvalidInput(fmt::format("{}.tip_diameter: {} tip diameters and {} forces, expected two or more of each, "
                                     "as many forces as diameters",
                                     where, d.size(), law.table_force.size()));
    }
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (!std::isfinite(d[i]) || d[i] <= 0 || (i > 0 && !(d[i] > d[i - 1]))) {
        throw InvalidInput(fmt::format("{}.tip_diameter: entry {} ({}) is not positive and increasing, expected "
                                       "strictly increasing tip diameters",
                                       where, i, um(d[i])));
      }
      if (!std::isfinite(law.table_force[i])) {
        throw InvalidInput(fmt::format("{}.force: entry {} is not finite", where, i));
      }
    }
  }
  if (!(law.valid_min_tip_diameter >= 0) ||
      (law.valid_max_tip_diameter && !(*law.valid_max_tip_diameter > law.valid_min_tip_diameter))) {
    throw InvalidInput(fmt::format("{}.valid_tip_diameter: [{}, {}] is empty, expected min < max", where,
                                   um(law.valid_min_tip_diameter),
                                   law.valid_max_tip_diameter ? um(*law.valid_max_tip_diameter) : "inf"));
  }
}

double equivalent_tip_diameter(double tip_area) { return std::sqrt(4 * std::max(tip_area, 0.0) / kPi); }

double puncture_force(double tip_area, const PunctureForceLaw& law) {
  if (law.kind == PunctureForceLawKind::Table) {  // linear interpolation, constant beyond the ends
    const double d = equivalent_tip_diameter(tip_area);
    const auto& x = law.table_tip_diameter;
    const auto& y = law.table_force;
    if (d <= x.front()) return y.front();
    if (d >= x.back()) return y.back();
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), d) - x.begin());
    return y[i - 1] + (y[i] - y[i - 1]) * (d - x[i - 1]) / (x[i] - x[i - 1]);
  }
  if (diameter_law(law.kind)) return law.slope * equivalent_tip_diameter(tip_area) + law.intercept;
  return law.slope * tip_area + law.intercept;  // Eq 4.2 and user linear-area laws
}

std::optional<std::string> puncture_force_validity_note(double tip_area, const PunctureForceLaw& law) {
  const double d = equivalent_tip_diameter(tip_area);
  double lo = law.valid_min_tip_diameter;
  std::optional<double> hi = law.valid_max_tip_diameter;
  if (law.kind == PunctureForceLawKind::Table && !law.table_tip_diameter.empty()) {
    lo = std::max(lo, law.table_tip_diameter.front());
    hi = hi ? std::min(*hi, law.table_tip_diameter.back()) : law.table_tip_diameter.back();
  }
  const double force = puncture_force(tip_area, law);
  const bool outside = d < lo * (1 - 1e-12) || (hi && d > *hi * (1 + 1e-12));
  if (!outside && force > 0) return std::nullopt;
  std::string range = fmt::format("equivalent tip diameters {} to {}", um(lo), hi ? um(*hi) : "any");
  return fmt::format("puncture force law {} used outside its validity range ({}): the tip's equivalent diameter is "
                     "{}, F = {:.4g} N{}",
                     to_string(law.kind), range, um(d), force,
                     force > 0 ? "" : " (not positive: |F| is used for buckling and bending, as in the dissertation)");
}

}  // namespace needlekit::analysis
