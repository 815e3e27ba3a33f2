// The fast per-sample evaluation of the uncertainty study gives the same events and index as
// analysis::performance_index() over random designs of every shape (solid and hollow, angled, short and long),
// including samples whose length or modulus differ from the nominal section's (where it uses the scaled factors).
#include <gtest/gtest.h>

#include <random>

#include "needlekit/uncertainty/design_outcome.hpp"

using namespace needlekit;

namespace {

uncertainty::DesignCase random_case(std::mt19937_64& rng, needle::Shape shape, bool hollow) {
  std::uniform_real_distribution<double> unit(0, 1);
  uncertainty::DesignCase c;
  needle::NeedleGeometry& n = c.design.needle;
  n.shape = shape;
  n.base_diameter = (60 + 200 * unit(rng)) * 1e-6;
  n.tip_diameter = shape == needle::Shape::Cylinder ? n.base_diameter : (20e-6 + 0.8 * unit(rng) * (n.base_diameter - 20e-6));
  n.bore_diameter = hollow ? 0.5 * n.tip_diameter * unit(rng) + 1e-6 : 0.0;
  n.length = (200 + 800 * unit(rng)) * 1e-6;
  c.design.material = materials::material_preset(unit(rng) < 0.5 ? "silicon" : "su-8");
  c.design.needles_per_row = 5 + static_cast<int>(10 * unit(rng));
  c.design.width = (3 + 7 * unit(rng)) * 1e-3;
  c.conditions.angle = unit(rng) < 0.3 ? 0.0 : 0.5 * unit(rng);
  c.conditions.target_depth = (20 + 100 * unit(rng)) * 1e-6;
  return c;
}

}  // namespace

TEST(DesignOutcome, AgreesWithPerformanceIndexOverRandomDesigns) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> unit(0, 1);
  int compared = 0, feasible = 0, buckled = 0, bent = 0;
  for (const needle::Shape shape : {needle::Shape::Cylinder, needle::Shape::Cone, needle::Shape::Bevel}) {
    for (const bool hollow : {false, true}) {
      for (int trial = 0; trial < 12; ++trial) {
        const uncertainty::DesignCase nominal = random_case(rng, shape, hollow);
        const uncertainty::DesignOutcomeEvaluator evaluator(nominal);
        // The nominal, then samples that change E, L, the tissue and the angle (the cached section) and one
        // that changes the tip (a new section).
        for (int sample = 0; sample < 4; ++sample) {
          uncertainty::DesignCase c = nominal;
          if (sample >= 1) {
            c.design.material.youngs_modulus *= 0.2 + 1.6 * unit(rng);
            c.design.needle.length *= 0.7 + 0.6 * unit(rng);
            c.conditions.tissue.alpha *= 0.5 + unit(rng);
            c.conditions.angle = 0.6 * unit(rng);
          }
          if (sample == 3 && shape != needle::Shape::Cylinder) c.design.needle.tip_diameter *= 0.9;
          const analysis::PerformanceIndexResult reference =
              analysis::performance_index(c.design, c.conditions, c.options);
          const uncertainty::DesignOutcome outcome = evaluator(uncertainty::design_values(c));
          ASSERT_TRUE(outcome.valid);
          EXPECT_EQ(outcome.buckles, !reference.buckling_ok);
          EXPECT_EQ(outcome.bends.has_value(), reference.bending_ok.has_value());
          if (outcome.bends && reference.bending_ok) EXPECT_EQ(*outcome.bends, !*reference.bending_ok);
          EXPECT_EQ(outcome.reaches_target, reference.permeation_depth > 0);
          EXPECT_NEAR(outcome.performance_index, reference.performance_index, 1e-12 * reference.performance_index);
          EXPECT_EQ(outcome.punctures, reference.cutting_depth > 0 && reference.puncture_force != 0);
          ++compared;
          feasible += reference.performance_index > 0;
          buckled += !reference.buckling_ok;
          bent += reference.bending_ok == false;
        }
      }
    }
  }
  // The comparison covers every branch: feasible designs, buckled and bent ones.
  EXPECT_EQ(compared, 3 * 2 * 12 * 4);
  EXPECT_GT(feasible, 20);
  EXPECT_GT(buckled, 5);
  EXPECT_GT(bent, 5);
}

TEST(DesignOutcome, InvalidSampledNeedleIsReportedNotThrown) {
  std::mt19937_64 rng(3);
  const uncertainty::DesignCase nominal = random_case(rng, needle::Shape::Cone, false);
  const uncertainty::DesignOutcomeEvaluator evaluator(nominal);
  uncertainty::DesignValues values = evaluator.nominal();
  values.needle.tip_diameter = 2 * values.needle.base_diameter;  // D1 > D2
  EXPECT_FALSE(evaluator(values).valid);
  values = evaluator.nominal();
  values.youngs_modulus = -1;
  EXPECT_FALSE(evaluator(values).valid);
}
