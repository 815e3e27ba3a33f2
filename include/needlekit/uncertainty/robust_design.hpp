// Robust design (issue 15): the array with the best nominal performance index among those whose probability of
// success on variable skin (design_uncertainty.hpp) is at least a given level, e.g. 0.99, and what that robustness
// costs in index against the deterministic optimum of §4.8.
//
// Method: the deterministic optimizer (analysis::optimize_design, brute force) ranks the grid by nominal index;
// the candidates are checked best first, each with its own uncertainty study (the spread of a design variable is
// centred on the candidate's value), until one meets the level. The first that does is the answer: every better
// design failed the check. Only the `max_candidates` best designs are checked; if none of them meets the level
// the result says so (status NotFound) with what was checked.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

namespace needlekit::uncertainty {

struct RobustDesignOptions {
  double min_success_probability = 0.99;  // (0, 1]: P(success) of the chosen design, point estimate
  PropagationOptions sampling;            // per candidate (Sobol' indices are not computed)
  analysis::OptimizerOptions optimizer;   // brute force; `top` is replaced by max_candidates
  int max_candidates = 2000;              // >= 1: nominal designs checked at most, best first
  // Called with the fraction done in [0, 1], never decreasing, from one thread at a time: the nominal ranking is the
  // first kRankingShare of it, candidate c of K ranked the part (c, c + 1) / K of the rest (1 once a design meets the
  // level). Return false to stop: robust_design throws needlekit::Interrupted. It replaces optimizer.progress and
  // sampling.progress.
  std::function<bool(double)> progress;
  static constexpr double kRankingShare = 0.2;
};

enum class RobustStatus {
  Found,     // a design meets the level
  NotFound,  // none of the checked candidates (or no feasible design) meets it
};
inline constexpr EnumTable<RobustStatus, 2> kRobustStatusNames{{
    {RobustStatus::Found, "found", "a design meets the level"},
    {RobustStatus::NotFound, "not_found", "none of the checked candidates (or no feasible design) meets it"},
}};
std::string_view to_string(RobustStatus status);

struct CandidateCheck {
  analysis::DesignCandidate candidate;
  double success_probability = 0;
  Interval ci95;
};

struct RobustDesignResult {
  RobustStatus status = RobustStatus::NotFound;
  std::string reason;
  double min_success_probability = 0;
  analysis::OptimizerResult nominal;         // the deterministic ranking (top: the candidates, best first)
  std::vector<CandidateCheck> checked;       // best nominal first; the last is the robust design when Found
  std::optional<CandidateCheck> robust;      // the best nominal design that meets the level
  double index_cost = 0;                     // 1/m: nominal optimum's index − robust design's index (>= 0)
  double index_cost_fraction = 0;            // index_cost / nominal optimum's index
};

// The design case of a candidate of a space (its needle, array, the space's material, tissue and target depth).
DesignCase candidate_case(const analysis::DesignSpace& space, const analysis::DesignCandidate& candidate,
                          const analysis::OptimizerOptions& optimizer);

// Throws InvalidInput for an invalid space or inputs (as optimize_design and design_uncertainty), a level outside
// (0, 1] or max_candidates < 1; Interrupted when options.progress returns false.
RobustDesignResult robust_design(const analysis::DesignSpace& space, const std::vector<DesignUncertainInput>& inputs,
                                 const std::vector<Correlation>& correlations, const RobustDesignOptions& options = {});

}  // namespace needlekit::uncertainty
