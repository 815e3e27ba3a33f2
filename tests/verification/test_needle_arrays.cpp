// Needle arrays pressed into a tissue block (issue 36): a 1 x 1 array is the single-needle run, needles far apart
// each carry the single needle's force, needles that the array's symmetry maps onto each other carry the same
// force, the quarter model gives the full model's forces, and the closer the needles stand the further the patch
// must travel before the first needle punctures (the "bed of nails"). 100 um flat punches (tip nodes, each punch's
// edge embedded in the top surface so that every needle sees the same nodes on its rim) on a 600 um gel block; the
// measured numbers are in docs/arrays.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/indentation_case.hpp"

using namespace needlekit;

namespace {


// `array` is the [array] table's lines or empty (one needle at the centre); `tissue` may give the width and length.
std::string case_text(const std::string& array, const std::string& tissue, const std::string& depth, int steps,
                      const std::string& pressure = "") {
  return R"(name = "array"
[needle]
shape = "cylinder"
tip_diameter = "100 um"
length = "500 um"
)" + (array.empty() ? std::string() : "[array]\n" + array + "\n") +
         R"([tissue]
height = "600 um"
)" + tissue + R"(
[[tissue.layers]]
name = "gel"
thickness = "rest"
youngs_modulus = "0.2 MPa"
poisson_ratio = 0.3
[mesh]
size_at_tip = "10 um"
size_far = "200 um"
refinement_radius = "70 um"
site_circle_radius = "50 um"
[loading]
depth = ")" + depth + R"("
steps = )" + std::to_string(steps) + R"(
continue_after_puncture = true
[model]
contact = "tip-nodes"
)" + (pressure.empty() ? std::string() : "[puncture]\ncritical_pressure = \"" + pressure + "\"\n");
}

insertion::IndentationResult run(const std::string& text) {
  const insertion::IndentationCase c = io::parse_indentation_case_toml(text, "case.toml");
  insertion::IndentationResult result = insertion::run_indentation(c);
  EXPECT_NE(result.status, insertion::IndentationStatus::SolverFailed) << result.reason;
  return result;
}

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

// The largest relative difference of the needles' last forces from their mean.
double spread(const insertion::IndentationResult& result, std::initializer_list<int> needles) {
  double mean = 0;
  for (int k : needles) mean += result.needles[k].force.back() / needles.size();
  double largest = 0;
  for (int k : needles) largest = std::max(largest, relative(result.needles[k].force.back(), mean));
  return largest;
}

TEST(NeedleArrays, OneByOneArrayIsTheSingleNeedle) {
  const std::string tissue = "width = \"1000 um\"\nlength = \"1000 um\"";
  const auto single = run(case_text("", tissue, "20 um", 4, "0.04 MPa"));
  const auto array = run(case_text("rows = 1\ncolumns = 1", tissue, "20 um", 4, "0.04 MPa"));
  ASSERT_EQ(single.steps.size(), array.steps.size());
  ASSERT_EQ(array.needles.size(), 1u);
  for (std::size_t k = 0; k < single.steps.size(); ++k) {
    EXPECT_LT(relative(array.steps[k].force, single.steps[k].force), 1e-6) << "step " << k + 1;
    EXPECT_LT(relative(array.needles[0].force[k], single.steps[k].force), 1e-6) << "step " << k + 1;
  }
  ASSERT_TRUE(single.puncture && array.puncture) << single.reason;
  EXPECT_LT(relative(array.puncture->depth, single.puncture->depth), 1e-6);
  EXPECT_LT(relative(array.puncture->force, single.puncture->force), 1e-6);
  ASSERT_TRUE(array.array);
  EXPECT_DOUBLE_EQ(array.array->punctured_fraction.back(), 1.0);
}

// Ten diameters apart, on a block whose margins are those of the single needle's block.
TEST(NeedleArrays, NeedlesTenDiametersApartEachCarryTheSingleNeedleForce) {
  const auto single = run(case_text("rows = 1\ncolumns = 1\nmargin = \"500 um\"", "", "10 um", 2));
  const auto array = run(case_text("rows = 2\ncolumns = 2\npitch = \"1000 um\"\nmargin = \"500 um\"", "", "10 um", 2));
  ASSERT_EQ(array.needles.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const double ratio = array.needles[k].force.back() / single.needles[0].force.back();
    RecordProperty("force_ratio_" + std::to_string(k), std::to_string(ratio));
    EXPECT_NEAR(ratio, 1.0, 0.02) << "needle " << k;
  }
}

TEST(NeedleArrays, NeedlesTheSymmetryMapsOntoEachOtherCarryTheSameForce) {
  const auto full = run(case_text("rows = 3\ncolumns = 3\npitch = \"300 um\"\nmargin = \"400 um\"", "", "10 um", 2));
  ASSERT_EQ(full.needles.size(), 9u);
  RecordProperty("corner_spread", std::to_string(spread(full, {0, 2, 6, 8})));
  RecordProperty("edge_spread", std::to_string(spread(full, {1, 3, 5, 7})));
  EXPECT_LT(spread(full, {0, 2, 6, 8}), 0.01);  // the corners
  EXPECT_LT(spread(full, {1, 3, 5, 7}), 0.01);  // the edges
  // Neighbours draw the surface down: the centre needle, with the most of them, carries the least.
  EXPECT_LT(full.needles[4].force.back(), full.needles[1].force.back());
  EXPECT_LT(full.needles[1].force.back(), full.needles[0].force.back());
}

// A hexagonal array, its block assembled from cells of two rows each (mesh/cell_replication.hpp): the needles that
// the half turn about the centre maps onto each other (the first row's onto the second's, so onto the cell's other
// site and its own mesh) carry the same force within the unstructured mesh's 1 %.
TEST(NeedleArrays, HexagonalNeedlesTheHalfTurnMapsOntoEachOtherCarryTheSameForce) {
  const auto full = run(case_text("layout = \"hexagonal\"\nrows = 2\ncolumns = 3\npitch = \"300 um\"\nmargin = \"400 um\"",
                                  "", "10 um", 2));
  ASSERT_EQ(full.needles.size(), 6u);
  for (int k = 0; k < 3; ++k) {
    RecordProperty("pair_" + std::to_string(k), std::to_string(spread(full, {k, 5 - k})));
    EXPECT_LT(spread(full, {k, 5 - k}), 0.01) << "needles " << k << " and " << 5 - k;
  }
}

// The 2 x 2 array's quarter model (one needle, symmetry planes between the needles) against the full model.
TEST(NeedleArrays, TheQuarterModelGivesTheFullModelsForces) {
  const std::string array = "rows = 2\ncolumns = 2\npitch = \"300 um\"\nmargin = \"400 um\"";
  const auto full = run(case_text(array, "", "10 um", 2));
  const auto quarter = run(case_text(array + "\nsymmetry = \"quarter\"", "", "10 um", 2));
  ASSERT_EQ(quarter.needles.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    RecordProperty("quarter_error_" + std::to_string(k),
                   std::to_string(relative(quarter.needles[k].force.back(), full.needles[k].force.back())));
    EXPECT_LT(relative(quarter.needles[k].force.back(), full.needles[k].force.back()), 0.01) << "needle " << k;
  }
  EXPECT_LT(relative(quarter.steps.back().force, full.steps.back().force), 0.01);
  EXPECT_LT(quarter.elements, full.elements / 2);
}

// Without embedded rims a square array's cell is mirrored from its quadrant (src/mesh/mirrored_cell.hpp): the block
// is as symmetric as the array, so the corner needles carry the same force to round-off, and the quarter model of a
// 3 x 3 array, whose planes run through the middle row and column (each needle there cut in half), is the full
// model's quarter, node for node: its forces are the full model's to the solver's tolerance.
TEST(NeedleArrays, TheQuarterModelThroughARowOfNeedlesIsTheFullModelsQuarter) {
  const auto without_rims = [](std::string text) {
    return text.erase(text.find("site_circle_radius"), text.find('\n', text.find("site_circle_radius")) -
                                                            text.find("site_circle_radius") + 1);
  };
  const std::string array = "rows = 3\ncolumns = 3\npitch = \"300 um\"\nmargin = \"400 um\"";
  const auto full = run(without_rims(case_text(array, "", "10 um", 2)));
  const auto quarter = run(without_rims(case_text(array + "\nsymmetry = \"quarter\"", "", "10 um", 2)));
  ASSERT_EQ(quarter.needles.size(), 9u);
  EXPECT_EQ(4 * quarter.elements, full.elements);
  EXPECT_LT(spread(full, {0, 2, 6, 8}), 1e-9);
  for (int k = 0; k < 9; ++k) {
    RecordProperty("quarter_error_" + std::to_string(k),
                   std::to_string(relative(quarter.needles[k].force.back(), full.needles[k].force.back())));
    EXPECT_LT(relative(quarter.needles[k].force.back(), full.needles[k].force.back()), 1e-6) << "needle " << k;
  }
}

// Bed of nails: at a fixed critical pressure, the plate travels further before the first needle punctures the closer
// the needles stand (quarter models of 2 x 2 arrays).
TEST(NeedleArrays, ThePlateTravelsFurtherToTheFirstPunctureTheCloserTheNeedles) {
  double previous = 0;
  for (const char* pitch : {"1200 um", "600 um", "300 um", "150 um"}) {
    const auto result = run(case_text(std::string("rows = 2\ncolumns = 2\nsymmetry = \"quarter\"\nmargin = \"400 um\"\n"
                                                  "pitch = \"") + pitch + "\"",
                                      "", "60 um", 30, "0.1 MPa"));
    ASSERT_TRUE(result.array && result.array->first_puncture_travel) << pitch << ": " << result.reason;
    const double travel = *result.array->first_puncture_travel;
    RecordProperty(std::string("first_puncture_travel_um_at_") + pitch, std::to_string(travel * 1e6));
    EXPECT_GT(travel, previous) << pitch;
    previous = travel;
  }
}

}  // namespace
