// Needle arrays pressed into a tissue block (issue 36): a 1 x 1 array is the single-needle run, needles far apart
// each carry the single needle's force, needles that the array's symmetry maps onto each other carry the same
// force, the quarter model gives the full model's forces, and the closer the needles stand the further the patch
// must travel before the first needle punctures (the "bed of nails"). Coarse Gmsh blocks of a 100 um cone; the
// measured numbers are in docs/arrays.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/indentation_case.hpp"

using namespace needlekit;

namespace {

// A cone (30 um tip, 100 um base, 500 um long) with rounded edges, surface contact, on a 600 um thick block of
// E = 0.2 MPa, nu = 0.3 (no locking of the linear tetrahedra), meshed coarsely. `needles` is an [array] or
// nothing (one needle at the centre); `tissue` may give the width and length.
std::string case_text(const std::string& needles, const std::string& tissue, const std::string& depth, int steps,
                      const std::string& pressure = "") {
  return R"(name = "array"
[needle]
shape = "cone"
tip_diameter = "30 um"
base_diameter = "100 um"
length = "500 um"
)" + needles + R"(
[tissue]
height = "600 um"
)" + tissue + R"(
[[tissue.layers]]
name = "gel"
thickness = "rest"
youngs_modulus = "0.2 MPa"
poisson_ratio = 0.3
[mesh]
size_at_tip = "15 um"
size_far = "200 um"
refinement_radius = "60 um"
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

TEST(NeedleArrays, OneByOneArrayIsTheSingleNeedle) {
  const std::string tissue = "width = \"1000 um\"\nlength = \"1000 um\"";
  const auto single = run(case_text("", tissue, "40 um", 4, "0.4 MPa"));
  const auto array = run(case_text("[array]\nrows = 1\ncolumns = 1", tissue, "40 um", 4, "0.4 MPa"));
  ASSERT_EQ(single.steps.size(), array.steps.size());
  ASSERT_EQ(array.needles.size(), 1u);
  for (std::size_t k = 0; k < single.steps.size(); ++k) {
    EXPECT_LT(relative(array.steps[k].force, single.steps[k].force), 1e-6) << "step " << k + 1;
    EXPECT_LT(relative(array.needles[0].force[k], single.steps[k].force), 1e-6) << "step " << k + 1;
  }
  ASSERT_TRUE(single.puncture && array.puncture);
  EXPECT_LT(relative(array.puncture->depth, single.puncture->depth), 1e-6);
  EXPECT_LT(relative(array.puncture->force, single.puncture->force), 1e-6);
  ASSERT_TRUE(array.array);
  EXPECT_DOUBLE_EQ(array.array->punctured_fraction.back(), 1.0);
}

}  // namespace
