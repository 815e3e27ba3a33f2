#include "needlekit/analysis/performance_index.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/analysis/bending.hpp"
#include "needlekit/analysis/skin_permeation.hpp"
#include "needlekit/core/errors.hpp"

namespace needlekit::analysis {

std::string_view to_string(PerformanceStatus status) { return name_of(kPerformanceStatusNames, status); }

namespace {

void validate_inputs(const ArrayDesign& d, const InsertionConditions& c, const PerformanceIndexOptions& o) {
  needle::validate(d.needle, "needle");
  materials::validate(d.material, "needle.material");
  validate(c.tissue, "tissue");
  if (d.needles_per_row < 1) {
    throw InvalidInput(fmt::format("array.needles_per_row: {} must be >= 1", d.needles_per_row));
  }
  if (!std::isfinite(d.width) || d.width <= 0) {
    throw InvalidInput(fmt::format("array.width: {} m must be a positive length", d.width));
  }
  if (!std::isfinite(c.angle) || c.angle < 0 || c.angle >= M_PI / 2) {
    throw InvalidInput(fmt::format("insertion.angle: {:.6g} deg must be in [0, 90) deg", c.angle * 180 / M_PI));
  }
  if (!std::isfinite(c.target_depth) || c.target_depth <= 0) {
    throw InvalidInput(fmt::format("insertion.target_depth: {} m must be a positive length", c.target_depth));
  }
  if (!(o.buckling_safety_factor >= 1) || !(o.bending_safety_factor >= 1)) {
    throw InvalidInput("safety factors must be >= 1");
  }
  if (!(o.gap_ratio >= 0) || !(o.spacing_factor >= 0)) {
    throw InvalidInput("gap_ratio and spacing_factor must be >= 0");
  }
}

std::string um(double metres) { return fmt::format("{:.4g} um", metres * 1e6); }

// The failed checks in the order they are found, with their explanations when asked for (formatted only then: the
// optimizer evaluates millions of designs).
class FailedChecks {
public:
  explicit FailedChecks(bool explain) : explain_(explain) {}
  template <class Explanation>
  void add(PerformanceStatus status, const Explanation& explanation) {
    failed_.push_back(status);
    if (explain_) text_.push_back(explanation());
  }
  // The status and the reason: Ok and the index (Eq 4.25 / Eq 5.9), or the first failed check and an index of 0.
  void finish(const PerformanceIndexOptions& options, PerformanceIndexResult& r) const {
    if (failed_.empty()) {
      const double pitch = options.index_pitch.value_or(r.pitch);
      r.performance_index = r.q_factor / (pitch * pitch * r.permeation_depth);
      r.status = PerformanceStatus::Ok;
      return;
    }
    r.performance_index = 0;
    r.status = failed_.front();
    for (PerformanceStatus check : failed_) r.failed_checks |= 1u << static_cast<unsigned>(check);
    if (explain_) r.reason = fmt::format("{}", fmt::join(text_, "; "));
  }

private:
  bool explain_;
  std::vector<PerformanceStatus> failed_;
  std::vector<std::string> text_;
};

// §4.2: puncture force, deformation and cutting depth.
void puncture_and_deformation(const needle::NeedleGeometry& n, const InsertionConditions& conditions,
                              PerformanceIndexResult& r) {
  r.tip_area = needle::tip_area(n);
  r.puncture_force = puncture_force(r.tip_area, conditions.tissue);
  r.puncture_force_law = conditions.tissue.force_law.kind;
  if (auto note = puncture_force_validity_note(r.tip_area, conditions.tissue.force_law)) {
    r.puncture_force_in_range = false;
    r.notes.push_back(*note);
  }
  const SkinDeformation deformation = skin_deformation(r.tip_area, conditions.tissue);
  r.deformation = deformation.depth;
  r.small_tip_branch = deformation.small_tip_branch;
  r.cutting_depth = cutting_depth(n.length, r.deformation);
  r.needle_volume = needle::volume(n);
}

// Tables 4.2–4.4: embedded volume, Q, hole and gap volumes, fractional skin volume.
void volumes(const needle::NeedleGeometry& n, const PerformanceIndexOptions& options, PerformanceIndexResult& r) {
  const double h = std::max(0.0, r.cutting_depth);
  r.diameter_at_surface = diameter_at_skin_surface(n, h);
  r.embedded_volume = embedded_volume(n, h);
  r.q_factor = permeation_factor(n, h);
  r.hole_volume = hole_volume(n, h, options.gap_ratio);
  r.gap_volume = gap_volume(n, h, options.gap_ratio);
  r.fractional_skin_volume = fractional_skin_volume(n, h, options.gap_ratio, r.pitch);
}

// §4.3, §5.2: buckling (φ) and bending (ω) under an insertion at angle θ.
void buckling_and_bending(const ArrayDesign& design, const InsertionConditions& conditions,
                          const PerformanceIndexOptions& options, std::optional<double> known_tapered_factor,
                          PerformanceIndexResult& r, FailedChecks& failed) {
  const needle::NeedleGeometry& n = design.needle;
  BucklingOptions buckling = options.buckling;
  buckling.explain = options.explain;
  r.buckling = critical_buckling_load(n, design.material, buckling, known_tapered_factor);
  r.buckling_force = angled_buckling_force(r.puncture_force, conditions.angle);
  r.buckling_ok = options.buckling_safety_factor * r.buckling_force < r.buckling.critical_load;  // Eq 4.5
  if (!r.buckling_ok) {
    failed.add(PerformanceStatus::Buckles, [&] {
      return fmt::format("buckles: force {:.4g} N >= critical buckling load {:.4g} N{}", r.buckling_force,
                         r.buckling.critical_load,
                         options.buckling_safety_factor > 1
                             ? fmt::format(" / safety factor {:.3g}", options.buckling_safety_factor)
                             : "");
    });
  }
  r.bending_force = angled_bending_force(r.puncture_force, conditions.angle);
  if (design.material.allowable_stress) {
    r.critical_bending_load = critical_bending_load(n, *design.material.allowable_stress);
    r.bending_ok = options.bending_safety_factor * r.bending_force < *r.critical_bending_load;
    if (!*r.bending_ok) {
      failed.add(PerformanceStatus::Bends, [&] {
        return fmt::format("bends: lateral force {:.4g} N >= critical bending load {:.4g} N", r.bending_force,
                           *r.critical_bending_load);
      });
    }
  } else if (r.bending_force > 0) {
    if (options.explain) r.notes.push_back("bending not assessed: the material has no allowable_stress");
  } else {
    r.bending_ok = true;  // no lateral force at θ = 0
    if (options.explain) {
      r.notes.push_back("bending load not assessed (no allowable_stress); no lateral force at angle 0");
    }
  }
  if (r.buckling.note.size()) r.notes.push_back(r.buckling.note);
}

}  // namespace

PerformanceIndexResult performance_index(const ArrayDesign& design, const InsertionConditions& conditions,
                                         const PerformanceIndexOptions& options,
                                         std::optional<double> known_tapered_factor) {
  validate_inputs(design, conditions, options);
  const auto& n = design.needle;
  PerformanceIndexResult r;
  FailedChecks failed(options.explain);
  puncture_and_deformation(n, conditions, r);

  // §4.8 constraint: the patch must hold n needles at a pitch of at least β·D2.
  r.pitch = design.width / design.needles_per_row;
  if (options.spacing_factor > 0 &&
      design.width < options.spacing_factor * design.needles_per_row * n.base_diameter * (1 - 1e-12)) {
    failed.add(PerformanceStatus::ConstraintViolated, [&] {
      return fmt::format("violates w >= beta*n*D2: width {} < {:.4g}*{}*{} = {}", um(design.width),
                         options.spacing_factor, design.needles_per_row, um(n.base_diameter),
                         um(options.spacing_factor * design.needles_per_row * n.base_diameter));
    });
  }

  // Eq 4.23: ideal permeation depth.
  r.permeation_depth = ideal_permeation_depth(n.hollow(), n.length, r.deformation, conditions.target_depth);
  if (r.permeation_depth <= 0) {
    failed.add(PerformanceStatus::TooShort, [&] {
      return fmt::format("does not reach the target depth: L = {} < d + T = {} + {}", um(n.length), um(r.deformation),
                         um(conditions.target_depth));
    });
  }
  volumes(n, options, r);
  buckling_and_bending(design, conditions, options, known_tapered_factor, r, failed);
  failed.finish(options, r);
  return r;
}

}  // namespace needlekit::analysis
