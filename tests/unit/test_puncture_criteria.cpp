// Puncture criteria (§3.5) on hand-made step histories: the critical pressure and the fracture energy fire where a
// hand calculation puts them (with linear interpolation between steps), the earliest one wins, and the two-insertion
// toughness (Eq 3.16) integrates the force difference exactly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/puncture_criteria.hpp"

using namespace needlekit;
using namespace needlekit::insertion;
using testing::HasSubstr;

namespace {

// A flat punch of radius a on a half-space (Sneddon): F = 2aEδ/(1-ν²), Δ = Fδ/2, A = πa² at every depth.
std::vector<PunctureSample> flat_punch(double a, double E, double nu, double step, int steps) {
  std::vector<PunctureSample> samples;
  for (int k = 1; k <= steps; ++k) {
    const double d = k * step;
    const double F = 2 * a * E * d / (1 - nu * nu);
    samples.push_back({d, F, M_PI * a * a, 0.5 * F * d});
  }
  return samples;
}

TEST(PunctureCriteria, CriticalPressureOfAFlatPunchMatchesSneddon) {
  const double a = 115e-6, E = 0.2e6, nu = 0.49, Pc = 0.663e6;
  // P = F/(πa²) = 2Eδ/(πa(1-ν²)) = Pc  =>  δ = Pc·π·a·(1-ν²)/(2E) = 455.1 um.
  const double expected = Pc * M_PI * a * (1 - nu * nu) / (2 * E);
  const auto point = critical_pressure_puncture(flat_punch(a, E, nu, 20e-6, 40), Pc);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->criterion, PunctureCriterion::CriticalPressure);
  EXPECT_NEAR(point->depth, expected, 1e-12);  // the pressure is linear in depth: interpolation is exact
  EXPECT_NEAR(point->force, Pc * M_PI * a * a, 1e-12);
  EXPECT_NEAR(expected, 455.1e-6, 0.1e-6);
}

TEST(PunctureCriteria, CriticalPressureInterpolatesBetweenSteps) {
  // Pressure 0.4, 0.6, 0.8 MPa on 1 um^2 of contact at 10, 20, 30 um: 0.663 is crossed 31.5 % past 20 um.
  const std::vector<PunctureSample> samples{{10e-6, 0.4, 1e-6, 0}, {20e-6, 0.6, 1e-6, 0}, {30e-6, 0.8, 1e-6, 0}};
  const auto point = critical_pressure_puncture(samples, 0.663e6);
  ASSERT_TRUE(point.has_value());
  EXPECT_NEAR(point->depth, 20e-6 + 0.315 * 10e-6, 1e-12);
  EXPECT_NEAR(point->force, 0.663, 1e-12);
}

TEST(PunctureCriteria, MetAtTheFirstSampleFiresThere) {
  // A sharp tip: the mean pressure under a cone does not depend on depth, so it fires at first contact.
  const std::vector<PunctureSample> samples{{2e-6, 1e-4, 1e-10, 0}, {4e-6, 4e-4, 4e-10, 0}};
  const auto point = critical_pressure_puncture(samples, 0.663e6);
  ASSERT_TRUE(point.has_value());
  EXPECT_DOUBLE_EQ(point->depth, 2e-6);
  EXPECT_DOUBLE_EQ(point->force, 1e-4);
}

TEST(PunctureCriteria, NoContactNoPuncture) {
  const std::vector<PunctureSample> samples{{10e-6, 0.0, 0.0, 0.0}, {20e-6, 0.0, 0.0, 0.0}};
  EXPECT_FALSE(critical_pressure_puncture(samples, 1.0).has_value());
  EXPECT_FALSE(fracture_energy_puncture(samples, 1.0).has_value());
  EXPECT_DOUBLE_EQ(contact_pressure(samples[0]), 0.0);
}

TEST(PunctureCriteria, FractureEnergyOfAFlatPunch) {
  // Δ = aEδ²/(1-ν²) = J·πa²  =>  δ = sqrt(J·π·a·(1-ν²)/E) = 370 um for J = 100 J/m².
  const double a = 115e-6, E = 0.2e6, nu = 0.49, J = 100;
  const double expected = std::sqrt(J * M_PI * a * (1 - nu * nu) / E);
  const auto samples = flat_punch(a, E, nu, 1e-6, 600);
  const auto point = fracture_energy_puncture(samples, J);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->criterion, PunctureCriterion::FractureEnergy);
  // Δ is quadratic in depth: linear interpolation on 1 um steps errs by less than (1 um)²/(8δ)·2.
  EXPECT_NEAR(point->depth, expected, 1e-9);
  EXPECT_NEAR(point->force, 2 * a * E * expected / (1 - nu * nu), 1e-3 * point->force);
}

TEST(PunctureCriteria, TheEarliestCriterionWins) {
  const double a = 115e-6, E = 0.2e6, nu = 0.49;
  const auto samples = flat_punch(a, E, nu, 5e-6, 200);
  PunctureOptions options;
  options.critical_pressure = 0.663e6;  // 455 um
  options.toughness = 100;              // 370 um
  auto point = puncture_point(samples, options);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->criterion, PunctureCriterion::FractureEnergy);
  options.toughness = 300;  // 641 um
  point = puncture_point(samples, options);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->criterion, PunctureCriterion::CriticalPressure);
  EXPECT_FALSE(puncture_point(samples, PunctureOptions{}).has_value());
}

TEST(PunctureCriteria, RejectsNonPositiveParameters) {
  PunctureOptions options;
  options.critical_pressure = -1;
  EXPECT_THAT([&] { validate(options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("puncture critical_pressure = -1 Pa: expected > 0 Pa")));
  options.critical_pressure.reset();
  options.toughness = 0;
  EXPECT_THAT([&] { validate(options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("puncture toughness = 0 N/m: expected > 0 N/m")));
}

TEST(TwoInsertionToughness, IntegratesTheForceDifference) {
  // First insertion F = 2x (N, x in m), second F' = x: ∫0^1mm (F - F') dx = 0.5e-6 J over a crack of 1e-8 m².
  ForceDepthCurve first{{0, 0.4e-3, 1e-3}, {0, 0.8e-3, 2e-3}};
  ForceDepthCurve second{{0, 0.25e-3, 0.5e-3, 1e-3}, {0, 0.25e-3, 0.5e-3, 1e-3}};
  ToughnessOptions options;
  options.crack_area = 1e-8;
  const ToughnessResult result = two_insertion_toughness(first, second, options);
  EXPECT_NEAR(result.energy, 0.5e-6, 1e-18);
  EXPECT_NEAR(result.toughness, 50.0, 1e-9);
  EXPECT_DOUBLE_EQ(result.max_depth, 1e-3);
  options.min_depth = 0.5e-3;  // ∫0.5^1 x dx = 0.375e-6
  EXPECT_NEAR(two_insertion_toughness(first, second, options).energy, 0.375e-6, 1e-18);
  options.max_depth = 0.75e-3;  // ∫0.5^0.75 x dx = 0.15625e-6
  EXPECT_NEAR(two_insertion_toughness(first, second, options).energy, 0.15625e-6, 1e-18);
}

TEST(TwoInsertionToughness, RejectsBadCurves) {
  ToughnessOptions options;
  options.crack_area = 1e-8;
  const ForceDepthCurve good{{0, 1e-3}, {0, 1}};
  EXPECT_THAT([&] { two_insertion_toughness({{0, 0}, {0, 1}}, good, options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("first insertion: depth")));
  EXPECT_THAT([&] { two_insertion_toughness(good, {{0}, {0}}, options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("second insertion: 1 samples")));
  EXPECT_THAT([&] { two_insertion_toughness(good, {{2e-3, 3e-3}, {0, 1}}, options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("is empty")));
  options.crack_area = 0;
  EXPECT_THAT([&] { two_insertion_toughness(good, good, options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("crack_area")));
}

}  // namespace
