#include "needlekit/uncertainty/design_uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/uncertainty/design_outcome.hpp"
#include "windowed_input.hpp"

namespace needlekit::uncertainty {
namespace {
// Mass outside the physical range too small to mention (one sample in 10^9).
constexpr double kNegligibleMass = 1e-9;
}  // namespace

namespace detail {

UncertainInput windowed_input(const DesignUncertainInput& input, double nominal, const InputRange& range,
                              std::string_view what, std::vector<std::string>& notes) {
  UncertainInput u{input.key, input.distribution, range.lower, range.upper};
  if (input.centred_on_nominal) u.distribution.mean = u.distribution.median = u.distribution.mode = nominal;
  validate(u.distribution, what);
  const double outside = mass_outside_window(u);
  const double factor = units::unit_factor(range.unit, range.dimension, what);
  if (outside > kMaxTruncatedMass) {
    throw InvalidInput(fmt::format(
        "{}: {} puts {:.3g} % of its samples outside the physical range [{:g}, {:g}) {} ({}), expected at most "
        "{:g} %: use truncated-normal with min and max, or a smaller spread",
        what, describe(u.distribution, factor, range.unit), 100 * outside, range.lower / factor, range.upper / factor,
        range.unit, range.meaning, 100 * kMaxTruncatedMass));
  }
  if (outside > kNegligibleMass) {
    notes.push_back(fmt::format("{}: {:.3g} % of {} lies outside the physical range and is truncated", input.key,
                                100 * outside, describe(u.distribution, factor, range.unit)));
  }
  return u;
}

InputTransform noted_transform(std::vector<UncertainInput> inputs, const std::vector<Correlation>& correlations,
                               std::vector<std::string>& notes) {
  InputTransform transform(std::move(inputs), correlations);
  if (transform.correlated()) {
    notes.push_back("correlated inputs: the Sobol' indices are those of the independent normal scores in the order "
                    "the inputs are given (the first input of a correlated pair carries the shared part)");
  }
  return transform;
}

}  // namespace detail

std::string_view to_string(DesignEvent event) { return name_of(kDesignEventNames, event); }

std::string_view to_string(UncertaintyStatus status) { return name_of(kUncertaintyStatusNames, status); }

struct DesignModel::Impl {
  DesignOutcomeEvaluator evaluator;
  std::vector<DesignInput> inputs;
  std::vector<OutputSpec> outputs;
};

DesignModel::DesignModel(const DesignCase& nominal, std::vector<DesignInput> inputs)
    : impl_(new Impl{DesignOutcomeEvaluator(nominal), std::move(inputs), {}}) {
  impl_->outputs.push_back({std::string(kPerformanceIndexOutput), OutputKind::Continuous});
  for (const EnumEntry<DesignEvent>& event : kDesignEventNames) {
    impl_->outputs.push_back({std::string(event.name), OutputKind::Indicator});
  }
}

DesignModel::~DesignModel() = default;

const std::vector<OutputSpec>& DesignModel::outputs() const { return impl_->outputs; }

void DesignModel::evaluate(const double* x, double* y) const {
  DesignValues values = impl_->evaluator.nominal();
  for (std::size_t i = 0; i < impl_->inputs.size(); ++i) set_value(impl_->inputs[i], x[i], values);
  const DesignOutcome r = impl_->evaluator(values);
  const auto flag = [](bool b) { return b ? 1.0 : 0.0; };
  if (!r.valid) {
    for (int o = 0; o < 6; ++o) y[o] = 0;
    y[1 + static_cast<int>(DesignEvent::InvalidSample)] = 1;
    return;
  }
  y[0] = r.performance_index;
  y[1 + static_cast<int>(DesignEvent::Puncture)] = flag(r.punctures);
  y[1 + static_cast<int>(DesignEvent::BucklingFailure)] = flag(r.buckles);
  y[1 + static_cast<int>(DesignEvent::BendingFailure)] =
      r.bends ? flag(*r.bends) : std::numeric_limits<double>::quiet_NaN();
  y[1 + static_cast<int>(DesignEvent::ReachesTarget)] = flag(r.reaches_target);
  y[1 + static_cast<int>(DesignEvent::Success)] =
      flag(r.punctures && !r.buckles && r.bends != true && r.reaches_target);
  y[1 + static_cast<int>(DesignEvent::InvalidSample)] = 0;
}

InputTransform design_input_transform(const DesignCase& nominal, const std::vector<DesignUncertainInput>& inputs,
                                      const std::vector<Correlation>& correlations, std::vector<std::string>& notes) {
  const DesignValues values = design_values(nominal);
  std::vector<UncertainInput> resolved;
  std::vector<DesignInput> seen;
  for (const DesignUncertainInput& input : inputs) {
    const std::string what = fmt::format("uncertain.\"{}\"", input.key);
    DesignInput which = design_input_from_key(input.key, what);
    nominal_value(which, values, what);
    if (values.needle.shape == needle::Shape::Cylinder && which == DesignInput::BaseDiameter) {
      which = DesignInput::TipDiameter;  // one diameter for a cylinder
    }
    if (std::find(seen.begin(), seen.end(), which) != seen.end()) {
      throw InvalidInput(fmt::format("{}: given twice (a cylinder's tip and base diameter are one input), expected "
                                     "each input once",
                                     what));
    }
    seen.push_back(which);
    const DesignInputInfo& entry = info(which);
    resolved.push_back(detail::windowed_input(input, nominal_value(which, values, what),
                                              {entry.dimension, entry.unit, entry.lower, entry.upper, entry.meaning},
                                              what, notes));
  }
  return detail::noted_transform(std::move(resolved), correlations, notes);
}

DesignUncertaintyResult design_uncertainty(const DesignCase& nominal, const std::vector<DesignUncertainInput>& inputs,
                                           const std::vector<Correlation>& correlations,
                                           const DesignUncertaintyOptions& options) {
  DesignUncertaintyResult result;
  result.nominal = analysis::performance_index(nominal.design, nominal.conditions, nominal.options);
  const InputTransform transform = design_input_transform(nominal, inputs, correlations, result.notes);
  std::vector<DesignInput> which;
  for (const DesignUncertainInput& input : inputs) {
    result.keys.push_back(input.key);
    which.push_back(design_input_from_key(input.key, input.key));
  }
  const DesignModel model(nominal, which);
  result.propagation = propagate(transform, model, options.sampling);

  const DesignValues values = design_values(nominal);
  std::vector<double> x(which.size()), y(model.outputs().size());
  for (std::size_t i = 0; i < which.size(); ++i) x[i] = nominal_value(which[i], values, inputs[i].key);
  for (std::size_t i = 0; i < which.size(); ++i) {
    OneAtATime oat{inputs[i].key, transform.value(i, 0.05), transform.value(i, 0.95), 0, 0};
    std::vector<double> varied = x;
    varied[i] = oat.low;
    model.evaluate(varied.data(), y.data());
    oat.index_low = y[0];
    varied[i] = oat.high;
    model.evaluate(varied.data(), y.data());
    oat.index_high = y[0];
    result.one_at_a_time.push_back(oat);
  }

  const OutputSummary& invalid = result.event(DesignEvent::InvalidSample);
  if (invalid.mean > 0) {
    result.status = UncertaintyStatus::InvalidSamples;
    result.reason = fmt::format("{} of {} samples made no valid needle (e.g. tip diameter above base diameter); they "
                                "count as failures with index 0",
                                std::llround(invalid.mean * static_cast<double>(invalid.defined)), invalid.defined);
  }
  const OutputSummary& bending = result.event(DesignEvent::BendingFailure);
  if (bending.defined < result.propagation.samples) {
    result.notes.push_back(fmt::format("bending_failure not assessed in {} of {} samples (the material has no "
                                       "allowable_stress and the angle is > 0); success counts them as not bending",
                                       result.propagation.samples - bending.defined, result.propagation.samples));
  }
  return result;
}

}  // namespace needlekit::uncertainty
