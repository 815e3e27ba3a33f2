#include "needlekit/analysis/puncture_model.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {

PunctureModel skin_puncture_model() { return PunctureModel{}; }

PunctureModel brain_puncture_model() {
  PunctureModel m;
  m.name = "brain";
  m.alpha = 0.0013;    // N, Table 6.5
  m.tau = 8507.6;      // 1/m (8.5076 /mm, Table 6.5; the table prints no unit, notes)
  return m;
}

std::vector<std::string> puncture_model_preset_names() { return {"skin", "brain"}; }

PunctureModel puncture_model_preset(std::string_view name, std::string_view what) {
  if (name == "skin") return skin_puncture_model();
  if (name == "brain") return brain_puncture_model();
  throw InvalidInput(fmt::format("{}: unknown tissue model '{}', expected \"skin\", \"brain\" or a table with "
                                 "alpha and tau",
                                 what, name));
}

void validate(const PunctureModel& m, std::string_view where) {
  auto positive = [&](double v, std::string_view key, std::string_view unit) {
    if (!std::isfinite(v) || v <= 0) {
      throw InvalidInput(fmt::format("{}.{}: {} {} must be positive and finite", where, key, v, unit));
    }
  };
  positive(m.alpha, "alpha", "N");
  positive(m.tau, "tau", "1/m");
  positive(m.small_tip_slope, "small_tip_slope", "1/m");
  validate(m.force_law, fmt::format("{}.puncture_force", where));
}

double puncture_force(double tip_area, const PunctureModel& m) {
  return puncture_force(tip_area, m.force_law);  // Eq 4.2 or the model's other law
}

SkinDeformation skin_deformation(double tip_area, const PunctureModel& m) {
  const double force = puncture_force(tip_area, m);
  if (force > m.alpha) return {std::log(force / m.alpha) / m.tau, false};  // Eq 4.3
  return {m.small_tip_slope * tip_area, true};                            // linear branch (notes)
}

double small_tip_area_limit(const PunctureModel& m) {
  // F(A) = α for the linear-area laws (Eq 4.2); the other laws are solved by bisection on F(A) - α (F increasing).
  if (m.force_law.kind == PunctureForceLawKind::Eq4_2 || m.force_law.kind == PunctureForceLawKind::LinearArea) {
    return (m.alpha - m.force_law.intercept) / m.force_law.slope;
  }
  double lo = 0, hi = 1e-12;
  while (puncture_force(hi, m) <= m.alpha && hi < 1) hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (puncture_force(mid, m) > m.alpha ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace needlekit::analysis
