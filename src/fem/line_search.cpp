#include "needlekit/fem/line_search.hpp"

#include <cmath>

namespace needlekit::fem {

LineSearchResult line_search(double potential0, double slope0,
                             const std::function<LineSearchPoint(double alpha)>& evaluate,
                             const LineSearchOptions& options) {
  LineSearchResult result;
  const auto sufficient = [&](const LineSearchPoint& p, double alpha) {
    return p.valid && p.potential <= potential0 + options.sufficient_decrease * alpha * slope0 +
                                         options.round_off * std::abs(potential0);
  };
  const auto at = [&](double alpha) {
    result.evaluations++;
    return evaluate(alpha);
  };
  LineSearchPoint accepted = at(1.0);
  if (sufficient(accepted, 1.0)) {
    // Expansion: a node on a needle's rounded edge is the case it is for — the rounding's curvature term
    // -p (I - n n^T - t t^T) / r of the exact contact Hessian is negative and left out of the solver's SPD tangent,
    // and without expansion such a node creeps round the rim by a factor ~1.2 per Newton iteration (the §6.2
    // cylinder under surface contact stopped on the iteration limit at 344 um).
    while (accepted.slope < options.expansion_slope * slope0 && 2 * result.step <= options.max_expansion) {
      const LineSearchPoint farther = at(2 * result.step);
      result.last_evaluation_at_step = false;
      if (!sufficient(farther, 2 * result.step) || farther.potential >= accepted.potential) break;
      result.step *= 2;
      accepted = farther;
      result.last_evaluation_at_step = true;
    }
    return result;
  }
  result.last_evaluation_at_step = false;
  for (int halving = 1; halving <= options.max_backtracks; ++halving) {
    result.step *= 0.5;
    if (sufficient(at(result.step), result.step)) {
      result.last_evaluation_at_step = true;
      return result;
    }
  }
  // No sufficient decrease (a kink of the contact energy or round-off): the full step; the caller's convergence test
  // and iteration limit decide.
  result.step = 1;
  result.failed = true;
  return result;
}

}  // namespace needlekit::fem
