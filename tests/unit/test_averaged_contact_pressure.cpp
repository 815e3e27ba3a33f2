// The averaged-pressure law (insertion/averaged_contact_pressure.hpp) on closed-form contact fields, sampled finely
// with exact cell resultants: a uniform pressure is its own average at every length; over a disc that holds the whole
// contact the average is the mean pressure F/A; on Sneddon's flat punch (square-root singular rim) the average near
// the rim follows 0.79 p_m (a/l)^(1/2) for l << a; on Hertz's sphere it tends to the peak pressure 3/2 p_m as l -> 0.
// Bad lengths are InvalidInput naming puncture.material_length, and the law fires where the samples cross p_c.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/averaged_contact_pressure.hpp"
#include "needlekit/insertion/puncture_criteria.hpp"

using namespace needlekit;
using namespace needlekit::insertion;

namespace {

// A disc of radius a cut into `rings` rings (finer towards the rim, where the fields change fastest) of `sectors`
// cells each, one point per cell at its mid-radius and mid-angle carrying the cell's exact resultant
// (2π ∫ p r dr / sectors, from `ring_force(r1, r2)`) and area.
std::vector<ContactPoint> disc_field(double a, int rings, int sectors,
                                     const std::function<double(double, double)>& ring_force) {
  std::vector<ContactPoint> points;
  for (int i = 0; i < rings; ++i) {
    const double s1 = static_cast<double>(i) / rings, s2 = static_cast<double>(i + 1) / rings;
    const double r1 = a * (1 - (1 - s1) * (1 - s1)), r2 = a * (1 - (1 - s2) * (1 - s2));
    for (int j = 0; j < sectors; ++j) {
      const double t = 2 * M_PI * (j + 0.5) / sectors, r = 0.5 * (r1 + r2);
      points.push_back({{r * std::cos(t), r * std::sin(t), 0.0},
                        ring_force(r1, r2) / sectors,
                        M_PI * (r2 * r2 - r1 * r1) / sectors});
    }
  }
  return points;
}

// Sneddon's flat punch, total force F: p = F / (2πa √(a² − r²)).
std::vector<ContactPoint> flat_punch_field(double a, double force) {
  return disc_field(a, 40, 240, [&](double r1, double r2) {
    return force / a * (std::sqrt(a * a - r1 * r1) - std::sqrt(a * a - r2 * r2));
  });
}

// Hertz's sphere, total force F: p = p0 √(1 − r²/a²), p0 = 3F/(2πa²).
std::vector<ContactPoint> hertz_field(double a, double force) {
  const double p0 = 3 * force / (2 * M_PI * a * a);
  return disc_field(a, 40, 240, [&](double r1, double r2) {
    const auto primitive = [&](double r) { return -p0 * a * a / 3 * std::pow(1 - r * r / (a * a), 1.5); };
    return 2 * M_PI * (primitive(r2) - primitive(r1));
  });
}

TEST(AveragedContactPressure, AUniformPressureIsItsOwnAverageAtEveryLength) {
  const double a = 100e-6, p = 0.4e6;
  const auto field = disc_field(a, 10, 40, [&](double r1, double r2) { return p * M_PI * (r2 * r2 - r1 * r1); });
  for (double l : {5e-6, 30e-6, 300e-6}) EXPECT_NEAR(averaged_peak_pressure(field, l) / p, 1.0, 1e-12) << l;
}

TEST(AveragedContactPressure, ADiscHoldingTheWholeContactGivesTheMeanPressure) {
  const double a = 100e-6, force = 2e-3, mean = force / (M_PI * a * a);
  EXPECT_NEAR(averaged_peak_pressure(flat_punch_field(a, force), 2.01 * a) / mean, 1.0, 1e-9);
  EXPECT_NEAR(averaged_peak_pressure(hertz_field(a, force), 2.01 * a) / mean, 1.0, 1e-9);
}

TEST(AveragedContactPressure, FlatPunchRimFollowsTheSquareRootOfTheLength) {
  // The half disc of radius l at the rim of p = C (2a s)^(-1/2) (s from the rim): p̄ = 0.787 p_m √(a/l) for l << a
  // (0.787 = Γ(1/4)√π/Γ(3/4) · (2/3) · (2/π) / (2√2)); so a flat punch punctures at p_m = 1.27 p_c √(l/a).
  const double a = 100e-6, force = 2e-3, mean = force / (M_PI * a * a);
  std::vector<double> ratio;
  for (double l : {5e-6, 10e-6, 20e-6}) {
    const double averaged = averaged_peak_pressure(flat_punch_field(a, force), l);
    ratio.push_back(averaged / mean);
    EXPECT_NEAR(averaged / mean / (0.787 * std::sqrt(a / l)), 1.0, 0.05) << "l = " << l;
  }
  EXPECT_GT(ratio[0], ratio[1]);
  EXPECT_GT(ratio[1], ratio[2]);
}

TEST(AveragedContactPressure, HertzTendsToThePeakPressure) {
  const double a = 100e-6, force = 2e-3, mean = force / (M_PI * a * a);
  const auto field = hertz_field(a, force);
  EXPECT_NEAR(averaged_peak_pressure(field, 4e-6) / mean, 1.5, 0.01);  // p0 = 3/2 p_m
  const double half = averaged_peak_pressure(field, 0.5 * a) / mean;
  EXPECT_LT(half, 1.5);
  EXPECT_GT(half, 1.0);
}

TEST(AveragedContactPressure, NoContactNoPressureAndBadLengthsAreNamed) {
  EXPECT_EQ(averaged_peak_pressure({}, 50e-6), 0.0);
  for (double l : {0.0, -50e-6, std::nan("")}) {
    try {
      averaged_peak_pressure({{{0, 0, 0}, 1e-3, 1e-8}}, l);
      ADD_FAILURE() << "no error for " << l;
    } catch (const InvalidInput& error) {
      EXPECT_THAT(error.what(), testing::StartsWith("puncture.material_length: "));
    }
  }
}

TEST(AveragedContactPressure, TheLawFiresWhereTheAveragedPressureCrossesItsCriticalValue) {
  PunctureOptions options;
  options.criterion = PunctureLaw::AveragedPressure;
  options.critical_pressure = 0.5e6;
  // p̄ = 0.2, 0.4, 0.6 MPa at 10, 20, 30 um: crosses 0.5 MPa half-way, at 25 um; the mean pressure F/A (1 MPa) is not
  // read.
  const std::vector<PunctureSample> samples{{10e-6, 1e-3, 1e-9, 0, 0.2e6},
                                            {20e-6, 2e-3, 2e-9, 0, 0.4e6},
                                            {30e-6, 3e-3, 3e-9, 0, 0.6e6}};
  const auto point = puncture_point(samples, options);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->criterion, PunctureCriterion::AveragedPressure);
  EXPECT_EQ(to_string(point->criterion), "averaged-pressure");
  EXPECT_NEAR(point->depth, 25e-6, 1e-15);
  EXPECT_NEAR(point->force, 2.5e-3, 1e-15);
  // The law needs its critical pressure, reads no toughness, and its length is checked against the table's range.
  options.critical_pressure.reset();
  EXPECT_THROW(validate(options), InvalidInput);
  options.critical_pressure = 0.5e6;
  options.toughness = 10;
  EXPECT_THAT([&] { validate(options); }, testing::ThrowsMessage<InvalidInput>(testing::StartsWith("puncture.toughness: ")));
  options.toughness.reset();
  options.material_length = -1e-6;
  EXPECT_THAT([&] { validate(options); },
              testing::ThrowsMessage<InvalidInput>(testing::HasSubstr("material_length = -1e-06 m: expected > 0 m")));
}

}  // namespace
