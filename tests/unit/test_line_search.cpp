// fem::line_search on one-dimensional potentials along a Newton direction whose tangent is right, too soft or too
// stiff, and on a potential whose full step is not admissible.
#include <gtest/gtest.h>

#include <cmath>

#include "needlekit/fem/line_search.hpp"

using namespace needlekit::fem;

namespace {

// The potential f(x) = h x^2 / 2 - g x seen along a Newton step taken with the tangent k: du = g / k, so along the
// step x = alpha g / k. Its minimiser is alpha* = k / h.
struct Quadratic {
  double h, g, k;
  LineSearchPoint operator()(double alpha) const {
    const double x = alpha * g / k;
    return {true, 0.5 * h * x * x - g * x, (h * x - g) * g / k};
  }
  double slope0() const { return -g * g / k; }
};

TEST(LineSearch, TheExactNewtonStepIsTakenWithOneEvaluation) {
  const Quadratic f{2.0, 3.0, 2.0};
  const auto r = line_search(0.0, f.slope0(), f);
  EXPECT_EQ(r.step, 1.0);
  EXPECT_EQ(r.evaluations, 1);
  EXPECT_TRUE(r.last_evaluation_at_step);
  EXPECT_FALSE(r.failed);
}

// A tangent 10x stiffer than the true curvature (a node on a needle's rounded edge, whose negative curvature term the
// solver's tangent leaves out): the full step goes a tenth of the way to the minimiser, and the expansion doubles it
// to 8, where the slope has fallen below half its start.
TEST(LineSearch, ExpandsWhenTheTangentIsTooStiff) {
  const Quadratic f{1.0, 1.0, 10.0};
  const auto r = line_search(0.0, f.slope0(), f);
  EXPECT_EQ(r.step, 8.0);
  EXPECT_TRUE(r.last_evaluation_at_step);
  EXPECT_EQ(r.evaluations, 4);  // 1, 2, 4, 8
  // Without expansion the step stays at a tenth of the minimiser's.
  LineSearchOptions off;
  off.max_expansion = 1;
  EXPECT_EQ(line_search(0.0, f.slope0(), f, off).step, 1.0);
}

// A concave direction (negative true curvature): the potential falls without bound, and the step stops at the cap.
TEST(LineSearch, ExpansionStopsAtItsCap) {
  const Quadratic f{-1.0, 1.0, 1.0};
  const auto r = line_search(0.0, f.slope0(), f);
  EXPECT_EQ(r.step, 64.0);
  EXPECT_TRUE(r.last_evaluation_at_step);
}

// A tangent too soft (4x below the curvature): the full step overshoots to where the potential is above its start, and
// backtracking halves it to 1/4, the minimiser, the first step with sufficient decrease.
TEST(LineSearch, BacktracksWhenTheTangentIsTooSoft) {
  const Quadratic f{4.0, 1.0, 1.0};
  const auto r = line_search(0.0, f.slope0(), f);
  EXPECT_EQ(r.step, 0.25);
  EXPECT_TRUE(r.last_evaluation_at_step);
  EXPECT_FALSE(r.failed);
}

// Steps beyond a quarter invert an element (not admissible): backtracking finds the admissible one.
TEST(LineSearch, InadmissibleStepsAreRefused) {
  const Quadratic f{1.0, 1.0, 1.0};
  const auto guarded = [&](double alpha) {
    LineSearchPoint p = f(alpha);
    p.valid = alpha <= 0.25;
    return p;
  };
  EXPECT_EQ(line_search(0.0, f.slope0(), guarded).step, 0.25);
}

// No step decreases the potential (round-off at convergence, or a kink): the full step is returned as failed.
TEST(LineSearch, ReturnsTheFullStepWhenNothingDecreases) {
  const auto flat = [](double) { return LineSearchPoint{true, 1.0, 0.0}; };
  const auto r = line_search(0.0, -1.0, flat);
  EXPECT_EQ(r.step, 1.0);
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.evaluations, 13);  // the full step and 12 halvings
}

}  // namespace
