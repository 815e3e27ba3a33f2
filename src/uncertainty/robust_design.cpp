#include "needlekit/uncertainty/robust_design.hpp"

#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"

namespace needlekit::uncertainty {

std::string_view to_string(RobustStatus status) { return name_of(kRobustStatusNames, status); }

DesignCase candidate_case(const analysis::DesignSpace& space, const analysis::DesignCandidate& c,
                          const analysis::OptimizerOptions& optimizer) {
  DesignCase design;
  design.design.needle = {space.shape, c.tip_diameter, c.base_diameter, c.bore_diameter, c.length};
  design.design.material = space.material;
  design.design.needles_per_row = c.needles_per_row;
  design.design.width = c.width;
  design.conditions = space.conditions;
  design.conditions.angle = 0;  // the optimizer inserts perpendicularly; an uncertain angle spreads around 0
  design.options.buckling = optimizer.buckling;
  design.options.buckling_safety_factor = optimizer.buckling_safety_factor;
  design.options.spacing_factor = space.spacing_factor;
  return design;
}

RobustDesignResult robust_design(const analysis::DesignSpace& space, const std::vector<DesignUncertainInput>& inputs,
                                 const std::vector<Correlation>& correlations, const RobustDesignOptions& options) {
  if (!(options.min_success_probability > 0 && options.min_success_probability <= 1)) {
    throw InvalidInput(fmt::format("min_success_probability: {} is outside (0, 1]", options.min_success_probability));
  }
  if (options.max_candidates < 1) {
    throw InvalidInput(fmt::format("max_candidates: {} must be >= 1", options.max_candidates));
  }
  RobustDesignResult result;
  result.min_success_probability = options.min_success_probability;
  analysis::OptimizerOptions optimizer = options.optimizer;
  optimizer.method = analysis::SearchMethod::BruteForce;
  optimizer.top = options.max_candidates;
  constexpr double ranking = RobustDesignOptions::kRankingShare;
  if (options.progress) optimizer.progress = [&](double f) { return options.progress(ranking * f); };
  result.nominal = analysis::optimize_design(space, optimizer);
  if (result.nominal.status == analysis::OptimizerStatus::Cancelled) throw Interrupted();
  if (result.nominal.top.empty()) {
    result.reason = fmt::format("no feasible nominal design: {}", result.nominal.reason);
    return result;
  }
  DesignUncertaintyOptions study;
  study.sampling = options.sampling;
  study.sampling.sobol_indices = false;
  const double candidates = static_cast<double>(result.nominal.top.size());
  for (const analysis::DesignCandidate& candidate : result.nominal.top) {
    if (options.progress) {
      const double checked = static_cast<double>(result.checked.size());
      study.sampling.progress = [&options, checked, candidates](double f) {
        return options.progress(ranking + (1 - ranking) * (checked + f) / candidates);
      };
    }
    const DesignUncertaintyResult r =
        design_uncertainty(candidate_case(space, candidate, optimizer), inputs, correlations, study);
    const OutputSummary& success = r.event(DesignEvent::Success);
    result.checked.push_back({candidate, success.mean, success.ci95});
    if (success.mean >= options.min_success_probability) {
      result.robust = result.checked.back();
      break;
    }
  }
  if (options.progress) options.progress(1.0);  // the answer is complete: a late stop changes nothing
  const double best = result.nominal.top.front().performance_index;
  if (result.robust) {
    result.status = RobustStatus::Found;
    result.index_cost = best - result.robust->candidate.performance_index;
    result.index_cost_fraction = result.index_cost / best;
  } else {
    result.reason = fmt::format("none of the {} best nominal designs reaches P(success) >= {:g} (best checked: {:.4g}); "
                                "raise max_candidates or widen the ranges",
                                result.checked.size(), options.min_success_probability,
                                std::max_element(result.checked.begin(), result.checked.end(),
                                                 [](const auto& a, const auto& b) {
                                                   return a.success_probability < b.success_probability;
                                                 })->success_probability);
  }
  return result;
}

}  // namespace needlekit::uncertainty
