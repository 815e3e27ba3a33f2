// The dissertation's published numbers of §6.3 (Table 6.1, §6.3.1, Table 6.3), read from tests/data/regression.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/analysis/sensitivity_sweep.hpp"

using namespace needlekit;
using namespace needlekit::analysis;

namespace {

nlohmann::json load(const std::string& name) {
  std::ifstream in(std::string(NEEDLEKIT_TEST_DATA_DIR) + "/regression/" + name);
  EXPECT_TRUE(in.good()) << name;
  return nlohmann::json::parse(in);
}

void expect_relative(double actual, double expected, double tolerance, const std::string& what) {
  if (expected == 0) {
    EXPECT_EQ(actual, 0) << what;
  } else {
    EXPECT_NEAR(actual / expected, 1.0, tolerance) << what << ": got " << actual << ", published " << expected;
  }
}

}  // namespace

TEST(Section_6_3_1, TableOfNeedlesReproducesPublishedNumbers) {
  const auto data = load("section_6_3_1.json");
  for (const auto& c : data["cases"]) {
    ArrayDesign design;
    design.needle.shape = needle::shape_from_string(c["shape"].get<std::string>());
    design.needle.tip_diameter = c["tip_diameter"].get<double>() * 1e-6;
    design.needle.base_diameter = c["base_diameter"].get<double>() * 1e-6;
    design.needle.bore_diameter = c["bore_diameter"].get<double>() * 1e-6;
    design.needle.length = 500e-6;
    design.material = materials::material_preset("silicon");
    design.needles_per_row = 10;
    design.width = 1e-2;
    const auto r = performance_index(design, InsertionConditions{});
    const std::string name = c["name"];
    const double tol = c["tolerance"];
    const auto& e = c["expect"];
    // The text truncates (42.98 -> "42.9"): compare deformation to the printed digits.
    expect_relative(r.deformation * 1e6, e["deformation"], name == "solid cone" || name == "hollow cone" ? 0.002 : tol,
                    name + " deformation");
    if (e.contains("cutting_depth")) expect_relative(r.cutting_depth * 1e6, e["cutting_depth"], tol, name + " h");
    expect_relative(r.performance_index * 1e-6, e["performance_index"], tol, name + " PI");
    EXPECT_EQ(std::string(to_string(r.status)), e["status"].get<std::string>()) << name << ": " << r.reason;
  }
}

TEST(Section_6_3_1, BevelTipAreaAndConeDeformationByHand) {
  // Bevel: segment of sagitta 30 um in a 120 um circle: 3600·acos(0.5) − 30·√2700 = 2211.065 um².
  needle::NeedleGeometry bevel{needle::Shape::Bevel, 30e-6, 120e-6, 0, 500e-6};
  EXPECT_NEAR(needle::tip_area(bevel) * 1e12, 2211.065, 1e-3);
  // Cone tip 30 um: A = 706.858 um², F(A) < alpha -> d = 0.0608·A = 42.977 um (notes' small-tip line).
  const auto d = skin_deformation(M_PI / 4 * 30e-6 * 30e-6, skin_puncture_model());
  EXPECT_TRUE(d.small_tip_branch);
  EXPECT_NEAR(d.depth * 1e6, 42.977, 1e-3);
}

class Table_6_3 : public testing::TestWithParam<std::size_t> {};

TEST_P(Table_6_3, OptimizerFindsThePublishedRow) {
  const auto row = load("table_6_3.json")["rows"][GetParam()];
  const auto shape = needle::shape_from_string(row["shape"].get<std::string>());
  DesignSpace space = figure_6_20_space(shape, row["hollow"]);
  OptimizerOptions options;
  options.top = 1;
  options.published_compat = row["published_compat"];
  const auto result = optimize_design(space, options);
  ASSERT_EQ(result.status, OptimizerStatus::Optimal) << result.reason;
  const auto& best = result.top.front();
  const std::string label = row["shape"].get<std::string>() + (row["hollow"] ? " hollow" : " solid");
  EXPECT_EQ(best.needles_per_row, row["n"].get<int>()) << label;
  EXPECT_NEAR(best.tip_diameter * 1e6, row["tip_diameter"].get<double>(), 1e-6) << label;
  EXPECT_NEAR(best.base_diameter * 1e6, row["base_diameter"].get<double>(), 1e-6) << label;
  EXPECT_NEAR(best.width * 1e6, row["width"].get<double>(), 1e-6) << label;
  EXPECT_NEAR(best.length * 1e6, row["length"].get<double>(), 1e-6) << label;
  expect_relative(best.performance_index * 1e-6, row["performance_index"], row["tolerance"], label + " PI");
  // The full evaluation of the reported design agrees with the optimizer's fast path.
  EXPECT_NEAR(best.details.performance_index / best.performance_index, 1.0, 1e-12) << label;
  // The certified method finds the same optimum.
  options.method = SearchMethod::Certified;
  const auto certified = optimize_design(space, options);
  ASSERT_EQ(certified.status, OptimizerStatus::Optimal);
  EXPECT_EQ(certified.top.front().needles_per_row, best.needles_per_row) << label;
  EXPECT_DOUBLE_EQ(certified.top.front().tip_diameter, best.tip_diameter) << label;
  EXPECT_DOUBLE_EQ(certified.top.front().base_diameter, best.base_diameter) << label;
  EXPECT_DOUBLE_EQ(certified.top.front().bore_diameter, best.bore_diameter) << label;
  EXPECT_DOUBLE_EQ(certified.top.front().width, best.width) << label;
  EXPECT_DOUBLE_EQ(certified.top.front().length, best.length) << label;
}

INSTANTIATE_TEST_SUITE_P(AllSixRows, Table_6_3, testing::Range<std::size_t>(0, 6));

TEST(Table_6_3, CorrectPitchFindsBetterHollowDesignsThanPublished) {
  for (auto shape : {needle::Shape::Cylinder, needle::Shape::Cone}) {
    const auto space = figure_6_20_space(shape, true);
    OptimizerOptions compat;
    compat.top = 1;
    compat.published_compat = true;
    OptimizerOptions correct = compat;
    correct.published_compat = false;
    const auto published = optimize_design(space, compat);
    const auto improved = optimize_design(space, correct);
    EXPECT_GT(improved.top.front().performance_index, published.top.front().performance_index * 1.5);
  }
}

// Figs 6.18/6.19: doubling D2 raises the cone's index most, then L, then D1 (published ×3.25, ×1.11, ×1.03 for the
// solid cone; the factors depend on an undocumented averaging and are not asserted, the ranking and directions
// are: notes). For hollow cones a longer needle lowers the index (the text: "opposite effect").
TEST(Figure_6_18, SensitivityRankingAndDirections) {
  auto doubling_ratio = [](bool hollow, SweepParameter parameter, double from) {
    ArrayDesign design;
    design.needle = {needle::Shape::Cone, 30e-6, 150e-6, hollow ? 20e-6 : 0.0, 500e-6};
    design.material = materials::material_preset("silicon");
    const auto sweep = sensitivity_sweep(design, {}, {}, {parameter, from, 2 * from, from});
    EXPECT_EQ(sweep.points.size(), 2u);
    return sweep.points[1].result.performance_index / sweep.points[0].result.performance_index;
  };
  const double base = doubling_ratio(false, SweepParameter::BaseDiameter, 150e-6);
  const double length = doubling_ratio(false, SweepParameter::Length, 500e-6);
  const double tip = doubling_ratio(false, SweepParameter::TipDiameter, 30e-6);
  EXPECT_GT(base, length);
  EXPECT_GT(length, tip);
  EXPECT_GT(tip, 1.0);
  EXPECT_GT(base, 3.0);
  EXPECT_GT(doubling_ratio(true, SweepParameter::BaseDiameter, 150e-6), 3.0);
  EXPECT_LT(doubling_ratio(true, SweepParameter::Length, 500e-6), 1.0);
}
