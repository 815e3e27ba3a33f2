// The certified optimizer returns exactly the brute-force optimum (value and the first design in loop order) on
// grids small enough to enumerate, including spaces where buckling, the spacing constraint and ties decide.
#include <gtest/gtest.h>

#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/core/errors.hpp"

using namespace needlekit;
using namespace needlekit::analysis;

namespace {

struct SpaceCase {
  std::string name;
  DesignSpace space;
};

std::vector<SpaceCase> spaces() {
  std::vector<SpaceCase> cases;
  for (auto shape : {needle::Shape::Cylinder, needle::Shape::Cone, needle::Shape::Bevel}) {
    for (bool hollow : {false, true}) {
      const std::string type = std::string(needle::to_string(shape)) + (hollow ? "-hollow" : "-solid");
      // A finer (5 um) slice of the Fig 6.20 space.
      DesignSpace fine = figure_6_20_space(shape, hollow);
      fine.needles_per_row = {15, 25, 1};
      fine.tip_diameter = {30e-6, 100e-6, 5e-6};
      fine.base_diameter = {30e-6, 160e-6, 5e-6};
      fine.bore_diameter = {10e-6, 30e-6, 5e-6};
      fine.width = {5000e-6, 8000e-6, 250e-6};
      fine.length = {300e-6, 500e-6, 10e-6};
      cases.push_back({type + " fine slice", fine});
      // A weak material on brain tissue with long needles, so that buckling limits the length.
      DesignSpace weak = fine;
      weak.material = materials::material_preset("plga");
      weak.conditions.tissue = brain_puncture_model();
      weak.conditions.target_depth = 1e-3;
      weak.length = {1000e-6, 3000e-6, 50e-6};
      weak.base_diameter = {40e-6, 300e-6, 10e-6};
      cases.push_back({type + " weak/brain", weak});
    }
  }
  return cases;
}

}  // namespace

TEST(CertifiedOptimum, EqualsBruteForce) {
  for (const auto& c : spaces()) {
    for (bool compat : {false, true}) {
      OptimizerOptions brute;
      brute.top = 1;
      brute.published_compat = compat;
      OptimizerOptions certified = brute;
      certified.method = SearchMethod::Certified;
      const auto a = optimize_design(c.space, brute);
      const auto b = optimize_design(c.space, certified);
      ASSERT_EQ(a.status, b.status) << c.name;
      if (a.status != OptimizerStatus::Optimal) continue;
      const auto& x = a.top.front();
      const auto& y = b.top.front();
      const std::string label = c.name + (compat ? " compat" : "");
      EXPECT_NEAR(y.performance_index / x.performance_index, 1.0, 1e-12) << label;
      EXPECT_EQ(y.needles_per_row, x.needles_per_row) << label;
      EXPECT_DOUBLE_EQ(y.tip_diameter, x.tip_diameter) << label;
      EXPECT_DOUBLE_EQ(y.base_diameter, x.base_diameter) << label;
      EXPECT_DOUBLE_EQ(y.bore_diameter, x.bore_diameter) << label;
      EXPECT_DOUBLE_EQ(y.width, x.width) << label;
      EXPECT_DOUBLE_EQ(y.length, x.length) << label;
      // The certified method evaluates far fewer points than the grid holds.
      EXPECT_LT(b.evaluated * 10, a.evaluated) << label;
    }
  }
}

TEST(CertifiedOptimum, BucklingLimitsTheWeakBrainDesigns) {
  DesignSpace weak = figure_6_20_space(needle::Shape::Cone, false);
  weak.material = materials::material_preset("plga");
  weak.conditions.tissue = brain_puncture_model();
  weak.conditions.target_depth = 1e-3;
  weak.length = {1000e-6, 3000e-6, 50e-6};
  OptimizerOptions options;
  options.top = 1;
  const auto result = optimize_design(weak, options);
  ASSERT_EQ(result.status, OptimizerStatus::Optimal);
  const auto& best = result.top.front();
  // The best design is at most as long as the longest one whose column still carries the puncture force.
  EXPECT_TRUE(best.details.buckling_ok);
  EXPECT_LT(best.details.buckling_force, best.details.buckling.critical_load);
}

TEST(Optimizer, RejectsHugeSpacesWithoutTheCertifiedMethodAndBadRanges) {
  DesignSpace huge = figure_6_20_space(needle::Shape::Cone, true);
  huge.tip_diameter.step = huge.base_diameter.step = huge.bore_diameter.step = 1e-6;
  huge.width.step = huge.length.step = 1e-7;
  EXPECT_THROW(optimize_design(huge), InvalidInput);
  DesignSpace empty = figure_6_20_space(needle::Shape::Cone, false);
  empty.length = {500e-6, 300e-6, 50e-6};
  EXPECT_THROW(optimize_design(empty), InvalidInput);
  DesignSpace zero_step = figure_6_20_space(needle::Shape::Cone, false);
  zero_step.width.step = 0;
  EXPECT_THROW(optimize_design(zero_step), InvalidInput);
}
