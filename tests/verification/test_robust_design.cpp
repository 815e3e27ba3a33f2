// Robust design: the design chosen is the best-ranked nominal design that meets the success level (every better
// one was checked and failed), its cost against the deterministic optimum is the index difference, and without
// spread the robust design is the deterministic optimum at no cost.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "needlekit/core/interrupt.hpp"
#include "needlekit/uncertainty/robust_design.hpp"

using namespace needlekit;
using uncertainty::DistributionKind;

namespace {

analysis::DesignSpace su8_cones() {
  analysis::DesignSpace space;
  space.shape = needle::Shape::Cone;
  space.material = materials::material_preset("su-8");
  space.needles_per_row = {5, 15, 1};
  space.tip_diameter = {40e-6, 100e-6, 10e-6};
  space.base_diameter = {100e-6, 250e-6, 25e-6};
  space.width = {5e-3, 10e-3, 1e-3};
  space.length = {400e-6, 700e-6, 50e-6};
  return space;
}

// Lognormal skin and insertions at up to 15 deg: the deterministic optimum of su8_cones is not robust there.
std::vector<uncertainty::DesignUncertainInput> variable_skin_at_an_angle() {
  return {{"tissue.alpha", {DistributionKind::Lognormal, 0, 0, 0.0183, 0.3}},
          {"insertion.angle", {DistributionKind::Uniform, 0, 0, 0, 0, 0, 15 * M_PI / 180}}};
}

}  // namespace

TEST(RobustDesign, BestNominalDesignThatMeetsTheLevel) {
  const analysis::DesignSpace space = su8_cones();
  const std::vector<uncertainty::DesignUncertainInput> inputs = variable_skin_at_an_angle();
  uncertainty::RobustDesignOptions options;
  options.min_success_probability = 0.99;
  options.sampling.samples = 512;
  const uncertainty::RobustDesignResult r = uncertainty::robust_design(space, inputs, {}, options);
  ASSERT_EQ(r.status, uncertainty::RobustStatus::Found) << r.reason;
  ASSERT_TRUE(r.robust);
  EXPECT_GE(r.robust->success_probability, 0.99);
  ASSERT_GE(r.checked.size(), 2u) << "the deterministic optimum is not robust here: the test must see a trade-off";
  for (std::size_t i = 0; i + 1 < r.checked.size(); ++i) {
    EXPECT_LT(r.checked[i].success_probability, 0.99) << i;  // every better design was refused
    EXPECT_GE(r.checked[i].candidate.performance_index, r.checked[i + 1].candidate.performance_index);
  }
  // The robust design is exactly the nominal ranking's entry at its position, and the cost is the difference.
  const analysis::DesignCandidate& chosen = r.robust->candidate;
  EXPECT_EQ(chosen.performance_index, r.nominal.top[r.checked.size() - 1].performance_index);
  EXPECT_DOUBLE_EQ(r.index_cost, r.nominal.top.front().performance_index - chosen.performance_index);
  EXPECT_GT(r.index_cost, 0.0);
  EXPECT_NEAR(r.index_cost_fraction, r.index_cost / r.nominal.top.front().performance_index, 1e-15);
}

TEST(RobustDesign, WithoutSpreadTheRobustDesignIsTheDeterministicOptimum) {
  const analysis::DesignSpace space = su8_cones();
  uncertainty::RobustDesignOptions options;
  options.sampling.samples = 16;
  const uncertainty::RobustDesignResult r = uncertainty::robust_design(
      space, {{"tissue.alpha", {DistributionKind::Lognormal, 0, 0, 0.0183, 0.0}}}, {}, options);
  ASSERT_EQ(r.status, uncertainty::RobustStatus::Found);
  EXPECT_EQ(r.checked.size(), 1u);
  EXPECT_EQ(r.robust->success_probability, 1.0);
  EXPECT_EQ(r.index_cost, 0.0);
}

TEST(RobustDesign, UnreachableLevelIsReportedWithWhatWasChecked) {
  const analysis::DesignSpace space = su8_cones();
  uncertainty::RobustDesignOptions options;
  options.min_success_probability = 1.0;
  options.max_candidates = 5;
  options.sampling.samples = 256;
  const uncertainty::RobustDesignResult r = uncertainty::robust_design(
      space, {{"insertion.angle", {DistributionKind::Uniform, 0, 0, 0, 0, 0, 60 * M_PI / 180}}}, {}, options);
  EXPECT_EQ(r.status, uncertainty::RobustStatus::NotFound);
  EXPECT_EQ(r.checked.size(), 5u);
  EXPECT_FALSE(r.robust);
  EXPECT_NE(r.reason.find("none of the 5 best nominal designs"), std::string::npos) << r.reason;
}

// The progress callback: the ranking is the first fifth, every candidate's sampling follows in order, the fractions
// never decrease and end at 1, the answer is the one without a callback; a callback that says stop ends the run.
TEST(RobustDesign, ProgressRisesToOneAndAStopInterrupts) {
  const analysis::DesignSpace space = su8_cones();
  const std::vector<uncertainty::DesignUncertainInput> inputs = variable_skin_at_an_angle();
  uncertainty::RobustDesignOptions options;
  options.min_success_probability = 0.99;
  options.sampling.samples = 256;
  const uncertainty::RobustDesignResult quiet = uncertainty::robust_design(space, inputs, {}, options);
  std::vector<double> fractions;
  options.progress = [&fractions](double f) {
    fractions.push_back(f);
    return true;
  };
  const uncertainty::RobustDesignResult r = uncertainty::robust_design(space, inputs, {}, options);
  ASSERT_EQ(r.checked.size(), quiet.checked.size());
  ASSERT_TRUE(r.robust && quiet.robust);
  EXPECT_EQ(r.robust->candidate.performance_index, quiet.robust->candidate.performance_index);
  ASSERT_GE(fractions.size(), 3u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_LE(fractions.front(), uncertainty::RobustDesignOptions::kRankingShare);
  // The first candidate's sampling ends at 0.2 + 0.8 / K: before the second one's starts.
  const double first_candidate_end = 0.2 + 0.8 / static_cast<double>(r.nominal.top.size());
  EXPECT_TRUE(std::any_of(fractions.begin(), fractions.end(),
                          [&](double f) { return std::abs(f - first_candidate_end) < 1e-12; }));
  options.progress = [](double f) { return f < 0.1; };  // stop during the ranking
  EXPECT_THROW(uncertainty::robust_design(space, inputs, {}, options), Interrupted);
}
