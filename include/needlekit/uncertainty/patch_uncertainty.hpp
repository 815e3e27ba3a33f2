// The probability that every needle of a patch works when the patch lands somewhere near its intended place and its
// needles and the skin vary: the placement (offsets of the centre along the patch axes, the rotation) and the
// needle's and tissue's inputs (design_inputs.hpp) are sampled; every sample places, fits and evaluates the patch
// (patch::fit_and_evaluate, dissertation ch. 5, §6.4) and records per needle the events of kDesignEventNames with
// the patch's own meanings (Eqs 5.2–5.12):
//   puncture          x_ij > d (Eqs 5.11, 5.12) and |F(A)| > 0,
//   buckling_failure  φ = 0: SF·|F|/cos θ >= P_cr (Eqs 5.3, 5.5),
//   bending_failure   ω = 0: SF·|F|·tan θ >= P_Be (Eqs 5.4, 5.7; undefined when not assessed and θ > 0),
//   reaches_target    min(x_ij, L) − d >= T (Eq 4.23 with the needle's own travel),
//   success           punctures, neither buckles nor bends, reaches the target (= the needle's status "ok").
// Patch-level outputs: the fraction of needles that succeed, P(all succeed) and P(fraction >= X) for each X of
// `success_fractions`. Sampling, intervals and reproducibility are those of propagate() (propagation.hpp).
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/patch/fit_and_evaluate.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

namespace needlekit::uncertainty {

// The inputs of a patch case that may be uncertain, declared once: the placement's own inputs, then the design
// inputs that the patch evaluation uses (all of design_inputs() but array.width, which is the patch size, and
// insertion.angle, which the fit decides).
enum class PlacementInput { OffsetU, OffsetV, Rotation };
struct PatchInputInfo {
  std::string_view key;        // "placement.offset_u", ..., or a design_inputs() key
  units::Dimension dimension;
  std::string_view unit;       // for messages and reports
  double lower, upper;         // physical range (SI)
  std::string_view meaning;
  std::optional<PlacementInput> placement;  // set for the placement's inputs
  std::optional<DesignInput> design;        // set for the design inputs
};
const std::vector<PatchInputInfo>& patch_inputs();
// Throws InvalidInput naming `what` and listing the keys for a key that is not a patch input.
const PatchInputInfo& patch_input_from_key(std::string_view key, std::string_view what);

// A patch case: the surface, the patch and how it is placed, fitted and evaluated (spring_geodesics is ignored).
struct PatchCase {
  const geometry::SurfaceMesh* surface = nullptr;
  patch::PatchDesignOptions design;
  patch::FitAndEvaluateOptions options;
};

// Resolves keys and physical ranges as design_input_transform() does (an unknown key, one the case does not have,
// an input given twice, too much mass outside the physical range are InvalidInput naming the key). Needs no surface.
InputTransform patch_input_transform(const patch::PatchDesignOptions& design, const patch::FitAndEvaluateOptions& options,
                                     const std::vector<DesignUncertainInput>& inputs,
                                     const std::vector<Correlation>& correlations, std::vector<std::string>& notes);

struct PatchUncertaintyOptions {
  PropagationOptions sampling;
  std::vector<double> success_fractions = {0.5, 0.9, 0.99};  // each in (0, 1]: P(fraction of successes >= X)
};

// The order of the model's outputs: kPatchOutputs, then one per success fraction, then per needle kDesignEventNames
// but invalid_sample (kNeedleEvents of them).
inline constexpr std::string_view kSuccessFractionOutput = "success_fraction";  // continuous, in [0, 1]
inline constexpr std::string_view kAllSucceedOutput = "all_succeed";            // indicator
inline constexpr std::size_t kPatchOutputs = 3;  // success_fraction, all_succeed, invalid_sample
inline constexpr std::size_t kNeedleEvents = 5;  // puncture .. success

struct PatchUncertaintyResult {
  UncertaintyStatus status = UncertaintyStatus::Ok;
  std::string reason;
  std::vector<std::string> keys;              // the uncertain inputs, as given
  patch::FitAndEvaluateResult nominal;        // the deterministic fit and evaluation
  std::vector<double> success_fractions;      // as in the options
  int needles = 0;
  PropagationResult propagation;
  std::vector<std::string> notes;

  const OutputSummary& success_fraction() const { return propagation.outputs[0]; }
  const OutputSummary& all_succeed() const { return propagation.outputs[1]; }
  const OutputSummary& invalid_sample() const { return propagation.outputs[2]; }
  const OutputSummary& at_least(std::size_t fraction) const { return propagation.outputs[kPatchOutputs + fraction]; }
  // event: puncture, buckling_failure, bending_failure, reaches_target or success.
  const OutputSummary& needle_event(int needle, DesignEvent event) const {
    return propagation.outputs[kPatchOutputs + success_fractions.size() + kNeedleEvents * needle +
                               static_cast<std::size_t>(event)];
  }
};

// Throws InvalidInput for an invalid case or nominal placement (as fit_and_evaluate), invalid inputs (see
// patch_input_transform) or options. A sample whose placement or needle is invalid (the centre lands where the
// surface faces away, a tip wider than the base) counts as invalid_sample: every event 0, status invalid_samples.
PatchUncertaintyResult patch_uncertainty(const PatchCase& patch_case, const std::vector<DesignUncertainInput>& inputs,
                                         const std::vector<Correlation>& correlations,
                                         const PatchUncertaintyOptions& options = {});

}  // namespace needlekit::uncertainty
