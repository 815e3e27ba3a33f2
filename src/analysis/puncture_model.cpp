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
  positive(m.force_slope, "force_slope", "N/m^2");
  positive(m.small_tip_slope, "small_tip_slope", "1/m");
  if (!std::isfinite(m.force_intercept)) {
    throw InvalidInput(fmt::format("{}.force_intercept: must be finite", where));
  }
}

double puncture_force(double tip_area, const PunctureModel& m) {
  return m.force_slope * tip_area + m.force_intercept;  // Eq 4.2
}

SkinDeformation skin_deformation(double tip_area, const PunctureModel& m) {
  const double force = puncture_force(tip_area, m);
  if (force > m.alpha) return {std::log(force / m.alpha) / m.tau, false};  // Eq 4.3
  return {m.small_tip_slope * tip_area, true};                            // linear branch (notes)
}

double small_tip_area_limit(const PunctureModel& m) { return (m.alpha - m.force_intercept) / m.force_slope; }

}  // namespace needlekit::analysis
