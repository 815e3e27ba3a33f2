// Needle arrays ([array] of indentation case files, insertion/needle_array.hpp): positions and footprints of square
// and hexagonal layouts, the block sized from the footprint and the margin, the reduced models' needles and
// multiplicities, and every bad input an InvalidInput naming FILE:LINE and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/needle_array.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/scale_warnings.hpp"
#include "../../src/insertion/array_model.hpp"
#include "../support/expect_invalid.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

// Line numbers matter: the error cases below name them. The cone's base is 230 um.
std::string array_case(const std::string& array_lines, const std::string& tissue_lines = "",
                       const std::string& depth = "100 um") {
  return R"(name = "patch"
[needle]
shape = "cone"
tip_diameter = "30 um"
base_diameter = "230 um"
length = "600 um"
[array]
)" + array_lines + R"(
[tissue]
preset = "skin-stiff-sc"
)" + tissue_lines + R"(
[loading]
depth = ")" + depth + R"("
)";
}

insertion::IndentationCase parsed(const std::string& text) { return io::parse_indentation_case_toml(text, "a.toml"); }

TEST(NeedleArray, SquarePositionsAreCentredAndRowMajor) {
  insertion::NeedleArray a;
  a.rows = 2;
  a.columns = 3;
  a.pitch = 500e-6;
  const std::vector<Eigen::Vector2d> p = insertion::array_positions(a);
  ASSERT_EQ(p.size(), 6u);
  EXPECT_NEAR(p[0].x(), -500e-6, 1e-15);
  EXPECT_NEAR(p[0].y(), -250e-6, 1e-15);
  EXPECT_NEAR(p[5].x(), 500e-6, 1e-15);
  EXPECT_NEAR(p[5].y(), 250e-6, 1e-15);
  const Eigen::Vector2d footprint = insertion::array_footprint(a, 200e-6);
  EXPECT_NEAR(footprint.x(), 1200e-6, 1e-15);
  EXPECT_NEAR(footprint.y(), 700e-6, 1e-15);
}

TEST(NeedleArray, HexagonalNeighboursAreOnePitchApart) {
  insertion::NeedleArray a;
  a.layout = insertion::ArrayLayout::Hexagonal;
  a.rows = 3;
  a.columns = 3;
  a.pitch = 600e-6;
  const std::vector<Eigen::Vector2d> p = insertion::array_positions(a);
  EXPECT_NEAR((p[1] - p[0]).norm(), a.pitch, 1e-12);  // along a row
  EXPECT_NEAR((p[3] - p[0]).norm(), a.pitch, 1e-12);  // to the shifted row above
  EXPECT_NEAR((p[4] - p[0]).norm(), a.pitch * std::sqrt(3.0), 1e-12);
  Eigen::Vector2d low = p[0], high = p[0];
  for (const Eigen::Vector2d& q : p) low = low.cwiseMin(q), high = high.cwiseMax(q);
  EXPECT_NEAR((low + high).norm(), 0.0, 1e-12);  // the footprint is centred
  EXPECT_NEAR(insertion::array_footprint(a, 0).x(), high.x() - low.x(), 1e-12);
}

TEST(NeedleArray, TheBlockIsTheFootprintPlusTheMargin) {
  const insertion::IndentationCase c =
      parsed(array_case("rows = 2\ncolumns = 3\npitch = \"500 um\"\nmargin = \"400 um\"\nbacking_plate = true"));
  ASSERT_TRUE(c.array);
  EXPECT_EQ(c.needles.size(), 6u);
  EXPECT_NEAR(c.block.width, 2 * 500e-6 + 230e-6 + 2 * 400e-6, 1e-12);
  EXPECT_NEAR(c.block.length, 500e-6 + 230e-6 + 2 * 400e-6, 1e-12);
  EXPECT_TRUE(c.array->backing_plate);
  // A given width is kept; the length still comes from the footprint.
  const insertion::IndentationCase wide =
      parsed(array_case("rows = 2\ncolumns = 3\npitch = \"500 um\"", "width = \"5000 um\""));
  EXPECT_NEAR(wide.block.width, 5000e-6, 1e-12);
  EXPECT_NEAR(wide.block.length, 500e-6 + 230e-6 + 2 * 1000e-6, 1e-12);
}

TEST(NeedleArray, TheQuarterModelKeepsOneNeedlePerSymmetryClass) {
  insertion::IndentationCase c = parsed(array_case("rows = 3\ncolumns = 3\npitch = \"500 um\"\nsymmetry = \"quarter\""));
  const insertion::detail::ArrayModel model = insertion::detail::array_model(c);
  ASSERT_TRUE(model.reduced);
  EXPECT_EQ(model.reduced->needles.size(), 4u);  // centre, two edge needles, corner
  EXPECT_EQ(model.reduced->solver.boundary, fem::BoundaryCondition::QuarterSymmetry);
  EXPECT_NEAR(model.reduced->block.width, c.block.width / 2, 1e-15);
  EXPECT_DOUBLE_EQ(model.factor, 4.0);
  // Every needle's multiplicity times the solved needles' images adds up to the factor: forces balance.
  std::vector<double> images(model.reduced->needles.size(), 0.0);
  for (std::size_t k = 0; k < model.source.size(); ++k) images[model.source[k]] += model.multiplicity[k];
  for (double sum : images) EXPECT_DOUBLE_EQ(sum, 4.0);
  EXPECT_DOUBLE_EQ(model.multiplicity[4], 4.0);  // the centre needle, on both planes
  EXPECT_DOUBLE_EQ(model.multiplicity[1], 2.0);  // an edge needle, on the plane x = 0
  EXPECT_DOUBLE_EQ(model.multiplicity[0], 1.0);  // a corner
  // The centre needle sits on the reduced block's corner x = min, y = min.
  const Eigen::Vector2d corner(-model.reduced->block.width / 2, -model.reduced->block.length / 2);
  EXPECT_NEAR((model.reduced->needles[model.source[4]].position - corner).norm(), 0.0, 1e-12);
}

TEST(NeedleArray, TheHalfModelOfAnOddHexagonalArrayBalances) {
  const insertion::IndentationCase c = parsed(
      array_case("layout = \"hexagonal\"\nrows = 3\ncolumns = 4\npitch = \"500 um\"\nsymmetry = \"half\""));
  const insertion::detail::ArrayModel model = insertion::detail::array_model(c);
  ASSERT_TRUE(model.reduced);
  EXPECT_EQ(model.reduced->needles.size(), 8u);  // the middle row and the row above
  EXPECT_EQ(model.reduced->solver.boundary, fem::BoundaryCondition::HalfSymmetry);
  std::vector<double> images(model.reduced->needles.size(), 0.0);
  for (std::size_t k = 0; k < model.source.size(); ++k) images[model.source[k]] += model.multiplicity[k];
  for (double sum : images) EXPECT_DOUBLE_EQ(sum, 2.0);
}

// The reduced models mirror every needle: a bevel (its face towards the azimuth) is its own mirror image across the
// plane that holds its azimuth, not across the one normal to it; a reduced model across that plane is of a patch with
// mirrored needles, which the run's notes say.
TEST(NeedleArray, ReducedModelsOfBevelsSayWhenTheyMirrorTheBevels) {
  const auto notes = [](const std::string& symmetry, const std::string& azimuth) {
    std::string text = array_case("rows = 2\ncolumns = 2\nsymmetry = \"" + symmetry + "\"");
    text.replace(text.find("shape = \"cone\""), 14, "shape = \"bevel\"");
    text.replace(text.find("\"30 um\""), 7, "\"5 um\"");
    std::string all;
    for (const std::string& note : io::indentation_scale_warnings(parsed(text + "azimuth = \"" + azimuth + "\"\n")))
      all += note + "\n";
    return all;
  };
  EXPECT_THAT(notes("half", "0 deg"), testing::Not(HasSubstr("mirror image")));
  EXPECT_THAT(notes("half", "180 deg"), testing::Not(HasSubstr("mirror image")));
  EXPECT_THAT(notes("quarter", "0 deg"), testing::AllOf(HasSubstr("across x = 0"), HasSubstr("at x < 0 are mirror"),
                                                        HasSubstr("use symmetry = \"half\" or \"none\"")));
  EXPECT_THAT(notes("quarter", "0 deg"), testing::Not(HasSubstr("across y = 0")));
  EXPECT_THAT(notes("half", "90 deg"), testing::AllOf(HasSubstr("across y = 0"), HasSubstr("use symmetry = \"none\"")));
  // A cone is its own mirror image across every plane through its axis.
  EXPECT_EQ(insertion::off_mirror_plane(parsed(array_case("rows = 2\ncolumns = 2\nsymmetry = \"quarter\"")), 0), 0.0);
  // The §6.2 sharp bevel's centroid (the figure the header cites).
  std::string bevel = array_case("rows = 2\ncolumns = 2\nsymmetry = \"half\"");
  bevel.replace(bevel.find("shape = \"cone\""), 14, "shape = \"bevel\"");
  bevel.replace(bevel.find("\"30 um\""), 7, "\"5 um\"");
  bevel.replace(bevel.find("\"600 um\""), 8, "\"1000 um\"");
  const double off_axis = insertion::off_mirror_plane(parsed(bevel), 0);
  RecordProperty("sharp_bevel_centroid_off_axis_um", std::to_string(off_axis * 1e6));
  EXPECT_NEAR(off_axis, 35.1e-6, 0.1e-6);
}

TEST(NeedleArray, BadInputNamesFileLineAndKey) {
  EXPECT_THAT([] { parsed(array_case("rows = 2\ncolumns = 2\npitch = \"200 um\"")); },
              testing::ThrowsMessage<InvalidInput>(
                  testing::AllOf(HasSubstr("a.toml:10"), HasSubstr("array.pitch"), HasSubstr("base diameter"))));
  EXPECT_THAT([] { parsed(array_case("layout = \"hexagonal\"\nrows = 3\ncolumns = 3\nsymmetry = \"quarter\"")); },
              testing::ThrowsMessage<InvalidInput>(testing::AllOf(HasSubstr("a.toml:11"), HasSubstr("array.symmetry"))));
  EXPECT_THAT([] { parsed(array_case("layout = \"hexagonal\"\nrows = 2\ncolumns = 3\nsymmetry = \"half\"")); },
              testing::ThrowsMessage<InvalidInput>(
                  testing::AllOf(HasSubstr("a.toml:11"), HasSubstr("array.symmetry"), HasSubstr("even"))));
  EXPECT_THAT([] { parsed(array_case("rows = 3\ncolumns = 3\npitch = \"600 um\"", "width = \"1000 um\"")); },
              testing::ThrowsMessage<InvalidInput>(
                  testing::AllOf(HasSubstr("a.toml:13"), HasSubstr("tissue.width"), HasSubstr("too small"))));
  EXPECT_THAT([] { parsed(array_case("layout = \"round\"")); },
              testing::ThrowsMessage<InvalidInput>(testing::AllOf(HasSubstr("a.toml:8"), HasSubstr("\"hexagonal\""))));
  EXPECT_THAT([] { parsed(array_case("rows = 0")); },
              testing::ThrowsMessage<InvalidInput>(testing::AllOf(HasSubstr("a.toml:8"), HasSubstr("rows"))));
  EXPECT_THAT([] { parsed(array_case("pitch = 600")); },
              testing::ThrowsMessage<InvalidInput>(testing::AllOf(HasSubstr("a.toml:8"), HasSubstr("pitch"))));
  EXPECT_THAT([] { parsed(array_case("rows = 2\n[[needles]]\nx = \"0 um\"")); },
              testing::ThrowsMessage<InvalidInput>(testing::AllOf(HasSubstr("needles"), HasSubstr("[array]"))));
  EXPECT_THAT([] { parsed(array_case("rows = 2\nbacking_plate = true", "", "700 um")); },
              testing::ThrowsMessage<InvalidInput>(
                  testing::AllOf(HasSubstr("loading.depth"), HasSubstr("backing plate"))));
}

}  // namespace
