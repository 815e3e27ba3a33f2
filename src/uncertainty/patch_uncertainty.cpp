#include "needlekit/uncertainty/patch_uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "needlekit/core/errors.hpp"
#include "windowed_input.hpp"

namespace needlekit::uncertainty {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The design values of a patch case (the array fields that a patch does not use stay at their defaults).
DesignValues patch_values(const patch::PatchDesignOptions& design, const patch::FitAndEvaluateOptions& options) {
  DesignValues v;
  v.needle = design.needle;
  v.youngs_modulus = design.material.youngs_modulus;
  v.yield_strength = design.material.yield_strength;
  v.allowable_stress = design.material.allowable_stress;
  v.tissue = options.evaluation.conditions.tissue;
  v.target_depth = options.evaluation.conditions.target_depth;
  return v;
}

void apply_values(const DesignValues& v, patch::PatchDesignOptions& design, patch::FitAndEvaluateOptions& options) {
  design.needle = v.needle;
  design.material.youngs_modulus = v.youngs_modulus;
  design.material.yield_strength = v.yield_strength;
  design.material.allowable_stress = v.allowable_stress;
  options.evaluation.conditions.tissue = v.tissue;
  options.evaluation.conditions.target_depth = v.target_depth;
}

double nominal_of(const PatchInputInfo& entry, const DesignValues& values, const patch::Placement& placement,
                  std::string_view what) {
  if (entry.design) return nominal_value(*entry.design, values, what);
  return *entry.placement == PlacementInput::Rotation ? placement.rotation : 0.0;
}

// The per-needle events of one evaluated needle, in kDesignEventNames order (puncture .. success).
void needle_events(const patch::NeedleState& s, const patch::PatchEvaluation& e, double length, double target,
                   double* y) {
  const bool punctures = s.penetrates && std::abs(e.reference.puncture_force) > 0;
  // Bending is not assessed when the material has no allowable stress and the needle meets the skin at an angle.
  const bool bending_assessed = e.reference.critical_bending_load || !(s.travel > 0 && s.angle > 0);
  const bool reaches = s.hits_surface && std::min(s.travel, length) - e.reference.deformation >= target;
  y[static_cast<int>(DesignEvent::Puncture)] = punctures;
  y[static_cast<int>(DesignEvent::BucklingFailure)] = s.buckles;
  y[static_cast<int>(DesignEvent::BendingFailure)] = bending_assessed ? static_cast<double>(s.bends) : kNaN;
  y[static_cast<int>(DesignEvent::ReachesTarget)] = reaches;
  y[static_cast<int>(DesignEvent::Success)] = punctures && !s.buckles && !s.bends && reaches;
}

class PatchModel : public Model {
public:
  PatchModel(const PatchCase& c, std::vector<const PatchInputInfo*> inputs, const patch::PatchFrame& frame,
             std::vector<double> fractions)
      : case_(c), inputs_(std::move(inputs)), frame_(frame), fractions_(std::move(fractions)),
        nominal_(patch_values(c.design, c.options)), needles_(c.design.needles_u * c.design.needles_v) {
    outputs_.push_back({std::string(kSuccessFractionOutput), OutputKind::Continuous});
    outputs_.push_back({std::string(kAllSucceedOutput), OutputKind::Indicator});
    outputs_.push_back({std::string(to_string(DesignEvent::InvalidSample)), OutputKind::Indicator});
    for (double f : fractions_) outputs_.push_back({fmt::format("at_least_{:g}_percent", 100 * f), OutputKind::Indicator});
    for (int k = 0; k < needles_; ++k) {
      for (std::size_t event = 0; event < kNeedleEvents; ++event) {
        outputs_.push_back({fmt::format("needle_{}.{}", k, kDesignEventNames[event].name), OutputKind::Indicator});
      }
    }
  }

  const std::vector<OutputSpec>& outputs() const override { return outputs_; }

  void evaluate(const double* x, double* y) const override {
    patch::PatchDesignOptions design = case_.design;
    patch::FitAndEvaluateOptions options = case_.options;
    options.spring_geodesics = false;
    DesignValues values = nominal_;
    double offset_u = 0, offset_v = 0;
    for (std::size_t i = 0; i < inputs_.size(); ++i) {
      const PatchInputInfo& entry = *inputs_[i];
      if (entry.design) {
        set_value(*entry.design, x[i], values);
      } else if (*entry.placement == PlacementInput::OffsetU) {
        offset_u = x[i];
      } else if (*entry.placement == PlacementInput::OffsetV) {
        offset_v = x[i];
      } else {
        options.placement.rotation = x[i];
      }
    }
    apply_values(values, design, options);
    if (offset_u != 0 || offset_v != 0) {
      // The centre moves along the nominal patch axes and drops onto the surface (its closest point).
      const Eigen::Vector3d moved = frame_.surface_point + offset_u * frame_.u + offset_v * frame_.v;
      options.placement.center_vertex.reset();
      options.placement.center = case_.surface->closest_point(moved).point;
    }
    const std::size_t fractions = fractions_.size();
    double* per_needle = y + kPatchOutputs + fractions;
    std::fill(y, y + outputs_.size(), 0.0);
    patch::FitAndEvaluateResult r;
    try {
      r = patch::fit_and_evaluate(*case_.surface, design, options);
    } catch (const InvalidInput&) {
      y[2] = 1;  // invalid_sample: every event 0
      return;
    }
    int successes = 0;
    for (int k = 0; k < needles_; ++k) {
      double* event = per_needle + kNeedleEvents * k;
      needle_events(r.evaluation.needles[k], r.evaluation, design.needle.length,
                    options.evaluation.conditions.target_depth, event);
      successes += event[static_cast<int>(DesignEvent::Success)] > 0;
    }
    const double fraction = static_cast<double>(successes) / needles_;
    y[0] = fraction;
    y[1] = successes == needles_;
    for (std::size_t f = 0; f < fractions; ++f) y[kPatchOutputs + f] = fraction >= fractions_[f];
  }

private:
  const PatchCase& case_;
  std::vector<const PatchInputInfo*> inputs_;
  patch::PatchFrame frame_;
  std::vector<double> fractions_;
  DesignValues nominal_;
  int needles_;
  std::vector<OutputSpec> outputs_;
};

}  // namespace

const std::vector<PatchInputInfo>& patch_inputs() {
  static const std::vector<PatchInputInfo> table = [] {
    using units::Dimension;
    std::vector<PatchInputInfo> t{
        {"placement.offset_u", Dimension::Length, "mm", -kInf, kInf,
         "offset of the patch centre along the nominal patch axis U (then onto the surface)", PlacementInput::OffsetU,
         std::nullopt},
        {"placement.offset_v", Dimension::Length, "mm", -kInf, kInf, "offset of the patch centre along the axis V",
         PlacementInput::OffsetV, std::nullopt},
        {"placement.rotation", Dimension::Angle, "deg", -kInf, kInf,
         "rotation about the approach axis (surface.rotation)", PlacementInput::Rotation, std::nullopt},
    };
    for (const DesignInputInfo& d : design_inputs()) {
      if (d.input == DesignInput::Width || d.input == DesignInput::Angle) continue;
      t.push_back({d.key, d.dimension, d.unit, d.lower, d.upper, d.meaning, std::nullopt, d.input});
    }
    return t;
  }();
  return table;
}

const PatchInputInfo& patch_input_from_key(std::string_view key, std::string_view what) {
  std::vector<std::string_view> keys;
  for (const PatchInputInfo& entry : patch_inputs()) {
    if (entry.key == key) return entry;
    keys.push_back(entry.key);
  }
  throw InvalidInput(fmt::format("{}: '{}' is not an input of the patch case, expected one of: {}", what, key,
                                 fmt::join(keys, ", ")));
}

InputTransform patch_input_transform(const patch::PatchDesignOptions& design, const patch::FitAndEvaluateOptions& options,
                                     const std::vector<DesignUncertainInput>& inputs,
                                     const std::vector<Correlation>& correlations, std::vector<std::string>& notes) {
  const DesignValues values = patch_values(design, options);
  std::vector<UncertainInput> resolved;
  std::vector<std::string_view> seen;
  for (const DesignUncertainInput& input : inputs) {
    const std::string what = fmt::format("uncertain.\"{}\"", input.key);
    const PatchInputInfo* entry = &patch_input_from_key(input.key, what);
    if (design.needle.shape == needle::Shape::Cylinder && entry->design == DesignInput::BaseDiameter) {
      entry = &patch_input_from_key("needle.tip_diameter", what);  // one diameter for a cylinder
    }
    if (std::find(seen.begin(), seen.end(), entry->key) != seen.end()) {
      throw InvalidInput(fmt::format("{}: given twice (a cylinder's tip and base diameter are one input), expected "
                                     "each input once",
                                     what));
    }
    seen.push_back(entry->key);
    resolved.push_back(detail::windowed_input(input, nominal_of(*entry, values, options.placement, what),
                                              {entry->dimension, entry->unit, entry->lower, entry->upper,
                                               entry->meaning},
                                              what, notes));
  }
  return detail::noted_transform(std::move(resolved), correlations, notes);
}

PatchUncertaintyResult patch_uncertainty(const PatchCase& c, const std::vector<DesignUncertainInput>& inputs,
                                         const std::vector<Correlation>& correlations,
                                         const PatchUncertaintyOptions& options) {
  if (!c.surface) throw InvalidInput("patch case: no surface");
  for (double f : options.success_fractions) {
    if (!(f > 0 && f <= 1)) {
      throw InvalidInput(fmt::format("success_fractions: {} is out of range, expected a fraction in (0, 1]", f));
    }
  }
  PatchUncertaintyResult result;
  patch::FitAndEvaluateOptions nominal_options = c.options;
  nominal_options.spring_geodesics = false;
  result.nominal = patch::fit_and_evaluate(*c.surface, c.design, nominal_options);
  result.needles = result.nominal.design.node_count();
  result.success_fractions = options.success_fractions;
  const InputTransform transform = patch_input_transform(c.design, c.options, inputs, correlations, result.notes);
  std::vector<const PatchInputInfo*> which;
  for (const DesignUncertainInput& input : inputs) {
    result.keys.push_back(input.key);
    which.push_back(&patch_input_from_key(input.key, input.key));
  }
  const PatchModel model(c, which, result.nominal.frame, options.success_fractions);
  result.propagation = propagate(transform, model, options.sampling);

  const OutputSummary& invalid = result.invalid_sample();
  if (invalid.mean > 0) {
    result.status = UncertaintyStatus::InvalidSamples;
    result.reason = fmt::format("{} of {} samples could not be placed or made no valid needle (e.g. the centre landed "
                                "where the surface faces away); they count as failures",
                                std::llround(invalid.mean * static_cast<double>(invalid.defined)), invalid.defined);
  }
  std::size_t undefined_bending = 0;
  for (int k = 0; k < result.needles; ++k) {
    undefined_bending += result.propagation.samples - result.needle_event(k, DesignEvent::BendingFailure).defined;
  }
  if (undefined_bending > 0) {
    result.notes.push_back(fmt::format("bending_failure not assessed for {} needle samples (the material has no "
                                       "allowable_stress and the needle meets the skin at an angle); success counts "
                                       "them as not bending",
                                       undefined_bending));
  }
  if (c.options.fit.kind == patch::PatchKind::Equilibrium) {
    result.notes.push_back("equilibrium fit: the load per node is the case's in every sample (it does not follow a "
                           "sampled tip or tissue)");
  }
  return result;
}

}  // namespace needlekit::uncertainty
