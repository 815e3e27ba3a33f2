// Line search of the quasi-static solver's Newton iterations on the total potential along a Newton direction:
// backtracking to Armijo's sufficient decrease, and expansion while the potential still falls steeply at the step
// (the bracketing phase of a Wolfe line search, Nocedal & Wright, Numerical Optimization, 2nd ed. 2006, Alg. 3.5).
// Written here rather than taken from Ceres or NLopt: those own their iterations, while here every evaluation is one
// of the solver's assemblies and the full step's is reused as the next Newton iteration's.
#pragma once
#include <functional>

namespace needlekit::fem {

// The potential along the direction at a step length alpha.
struct LineSearchPoint {
  bool valid = true;     // false: the step is not admissible (an element inverted)
  double potential = 0;  // J
  double slope = 0;      // J, d potential / d alpha at alpha; read only for alpha >= 1 (the expansion)
};

struct LineSearchOptions {
  double sufficient_decrease = 1e-4;  // Armijo's c1: potential <= potential0 + c1 alpha slope0
  double round_off = 1e-10;           // relative slack of the potential for round-off in the comparison
  int max_backtracks = 12;            // halvings before the line search gives up (and returns the full step)
  // Expansion: the step doubles while the slope at the step is still below this fraction of slope0 (the curvature
  // condition fails: the tangent is stiffer than the true Hessian along the direction) and the potential keeps
  // falling, up to max_expansion times the Newton step. 0 < expansion_slope < 1; max_expansion = 1 turns it off.
  double expansion_slope = 0.5;
  double max_expansion = 64;
};

struct LineSearchResult {
  double step = 1;                     // the accepted step length
  bool failed = false;                 // no sufficient decrease within max_backtracks: the full step is returned
  bool last_evaluation_at_step = true;  // the last call of `evaluate` was at `step` (its assembly can be reused)
  int evaluations = 0;
};

// `potential0` and `slope0` (< 0, a descent direction) at alpha = 0; `evaluate(alpha)` the potential at alpha.
// Evaluates alpha = 1 first; then halves it until the potential falls enough, or, when the full step is accepted,
// doubles it while the curvature condition fails.
LineSearchResult line_search(double potential0, double slope0,
                             const std::function<LineSearchPoint(double alpha)>& evaluate,
                             const LineSearchOptions& options = {});

}  // namespace needlekit::fem
