// The probability that a needle-array design works on variable skin: the design's uncertain inputs (design_inputs
// .hpp) are sampled, every sample is evaluated (design_outcome.hpp), and the result gives each event's probability
// with its 95 % interval, the distribution of the performance index and the Sobol' indices of both
// (propagation.hpp).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/uncertainty/design_inputs.hpp"
#include "needlekit/uncertainty/propagation.hpp"

namespace needlekit::uncertainty {

// The events, declared once: {event, "name", "meaning"}; outputs 1..6 of the design model (output 0 is the index).
enum class DesignEvent { Puncture, BucklingFailure, BendingFailure, ReachesTarget, Success, InvalidSample };
inline constexpr EnumTable<DesignEvent, 6> kDesignEventNames{{
    {DesignEvent::Puncture, "puncture", "the needle punctures: |F(A)| > 0 and cutting depth L - d > 0"},
    {DesignEvent::BucklingFailure, "buckling_failure", "phi = 0: the axial force reaches the critical buckling load"},
    {DesignEvent::BendingFailure, "bending_failure",
     "omega = 0: the lateral force reaches the critical bending load (undefined where not assessed)"},
    {DesignEvent::ReachesTarget, "reaches_target", "L - d >= T: the tip reaches the target depth"},
    {DesignEvent::Success, "success", "punctures, neither buckles nor bends, and reaches the target"},
    {DesignEvent::InvalidSample, "invalid_sample", "the sampled values make no valid needle (counted as failure)"},
}};
std::string_view to_string(DesignEvent event);

// The name of output 0, the performance index (1/m).
inline constexpr std::string_view kPerformanceIndexOutput = "performance_index";

// An uncertain input as the user gave it.
struct DesignUncertainInput {
  std::string key;            // a key of design_inputs(), e.g. "needle.tip_diameter"
  Distribution distribution;  // SI
  // The normal's mean, the lognormal's median or the triangular's mode is the design's value of the input (set when
  // the study runs, so that robust design can centre the spread on every candidate).
  bool centred_on_nominal = false;
};

// The sampled model: inputs in the order given, outputs {performance_index, kDesignEventNames...}.
class DesignModel : public Model {
public:
  DesignModel(const DesignCase& nominal, std::vector<DesignInput> inputs);
  ~DesignModel() override;
  const std::vector<OutputSpec>& outputs() const override;
  void evaluate(const double* x, double* y) const override;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Resolves keys and physical ranges. Throws InvalidInput naming the key: an unknown key, a key the design does not
// have, an input given twice (a cylinder's tip and base diameter count as one), more than kMaxTruncatedMass of the
// distribution outside the physical range. `notes` receives one line per truncated input.
InputTransform design_input_transform(const DesignCase& nominal, const std::vector<DesignUncertainInput>& inputs,
                                      const std::vector<Correlation>& correlations, std::vector<std::string>& notes);

enum class UncertaintyStatus {
  Ok,              // every sample was a valid design
  InvalidSamples,  // some samples made an invalid design (e.g. D1 > D2); they count as failures (reason: how many)
};
inline constexpr EnumTable<UncertaintyStatus, 2> kUncertaintyStatusNames{{
    {UncertaintyStatus::Ok, "ok", "every sample was a valid design"},
    {UncertaintyStatus::InvalidSamples, "invalid_samples",
     "some samples made an invalid design; they count as failures"},
}};
std::string_view to_string(UncertaintyStatus status);

struct DesignUncertaintyOptions {
  PropagationOptions sampling;
};

// One-at-a-time sensitivity (as Figs 6.18, 6.19): the index with one input at its 5 % and 95 % quantiles and every
// other input at the design's value, to set beside the Sobol' indices.
struct OneAtATime {
  std::string key;
  double low = 0, high = 0;              // SI, the input's 5 % and 95 % quantiles
  double index_low = 0, index_high = 0;  // 1/m
};

struct DesignUncertaintyResult {
  UncertaintyStatus status = UncertaintyStatus::Ok;
  std::string reason;
  std::vector<std::string> keys;       // the uncertain inputs, as given
  analysis::PerformanceIndexResult nominal;  // the deterministic evaluation at the nominal values
  PropagationResult propagation;       // outputs: performance_index, then kDesignEventNames
  std::vector<OneAtATime> one_at_a_time;  // per input
  std::vector<std::string> notes;      // truncations, correlation caveats, events not assessed

  const OutputSummary& index() const { return propagation.outputs[0]; }
  const OutputSummary& event(DesignEvent event) const { return propagation.outputs[1 + static_cast<int>(event)]; }
};

// Throws InvalidInput for an invalid nominal case, invalid inputs (see design_input_transform) or options.
DesignUncertaintyResult design_uncertainty(const DesignCase& nominal, const std::vector<DesignUncertainInput>& inputs,
                                           const std::vector<Correlation>& correlations,
                                           const DesignUncertaintyOptions& options = {});

}  // namespace needlekit::uncertainty
