// Design and design-space files: the examples parse to the dissertation's inputs, and every bad input is an
// InvalidInput or IoError whose message names the file, the line and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/design_config.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

const std::filesystem::path kExamples = std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "examples";

// Line numbers matter: the cases below name them.
constexpr std::string_view kDesign = R"([needle]
shape = "cone"
tip_diameter = "30 um"
base_diameter = "150 um"
length = "500 um"
material = "silicon"

[array]
needles_per_row = 10
width = "1 cm"

[tissue]
model = "skin"

[insertion]
target_depth = "50 um"
)";

constexpr std::string_view kSpace = R"(shape = "cone"
hollow = false
material = "silicon"
target_depth = "50 um"

[ranges]
needles_per_row = [5, 25, 1]
tip_diameter = ["30 um", "150 um", "10 um"]
base_diameter = ["30 um", "300 um", "10 um"]
width = ["5000 um", "10000 um", "1000 um"]
length = ["300 um", "500 um", "50 um"]
)";

// `text` with the first occurrence of `from` replaced by `to`.
std::string replaced(std::string_view text, std::string_view from, std::string_view to) {
  std::string result(text);
  const std::size_t at = result.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) result.replace(at, from.size(), to);
  return result;
}

// The message of the Error that `call` throws ("" and a test failure if it throws nothing or something else).
template <class Error>
std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  } catch (const std::exception& other) {
    ADD_FAILURE() << "threw another exception: " << other.what();
    return "";
  }
  ADD_FAILURE() << "did not throw";
  return "";
}

struct BadCase {
  std::string_view from;  // a line of the base text
  std::string_view to;    // its bad replacement (may add lines)
  std::string location;   // "bad.toml:LINE:"
  std::string key;        // the key the message must name
  std::string problem;    // a word of the explanation
};

void expect_design_error(const BadCase& c) {
  SCOPED_TRACE(std::string(c.to));
  const std::string message = message_of<InvalidInput>([&] { io::parse_design_toml(replaced(kDesign, c.from, c.to), "bad.toml"); });
  EXPECT_THAT(message, testing::StartsWith(c.location));
  EXPECT_THAT(message, HasSubstr(c.key));
  EXPECT_THAT(message, HasSubstr(c.problem));
}

void expect_space_error(const BadCase& c) {
  SCOPED_TRACE(std::string(c.to));
  const std::string message = message_of<InvalidInput>([&] { io::parse_space_toml(replaced(kSpace, c.from, c.to), "space.toml"); });
  EXPECT_THAT(message, testing::StartsWith(c.location));
  EXPECT_THAT(message, HasSubstr(c.key));
  EXPECT_THAT(message, HasSubstr(c.problem));
}

}  // namespace

TEST(DesignConfig, Table6_1ExamplesGiveTheDissertationInputs) {
  const io::DesignFile cone = io::read_design_file(kExamples / "evaluate_table_6_1_cone.toml");
  EXPECT_EQ(cone.design.needle.shape, needle::Shape::Cone);
  EXPECT_DOUBLE_EQ(cone.design.needle.tip_diameter, 30e-6);
  EXPECT_DOUBLE_EQ(cone.design.needle.base_diameter, 150e-6);
  EXPECT_EQ(cone.design.needle.bore_diameter, 0);
  EXPECT_DOUBLE_EQ(cone.design.needle.length, 500e-6);
  EXPECT_EQ(cone.design.material.name, "silicon");
  EXPECT_DOUBLE_EQ(cone.design.material.youngs_modulus, 169e9);
  EXPECT_EQ(cone.design.needles_per_row, 10);
  EXPECT_DOUBLE_EQ(cone.design.width, 1e-2);
  EXPECT_EQ(cone.conditions.tissue.name, "skin");
  EXPECT_DOUBLE_EQ(cone.conditions.target_depth, 50e-6);
  EXPECT_EQ(cone.conditions.angle, 0);
  EXPECT_EQ(cone.options.spacing_factor, 3.0);

  const io::DesignFile cylinder = io::read_design_file(kExamples / "evaluate_table_6_1_cylinder_hollow.toml");
  EXPECT_EQ(cylinder.design.needle.shape, needle::Shape::Cylinder);
  EXPECT_DOUBLE_EQ(cylinder.design.needle.base_diameter, 95e-6);  // omitted: the tip diameter
  EXPECT_DOUBLE_EQ(cylinder.design.needle.bore_diameter, 20e-6);

  const io::DesignFile bevel = io::read_design_file(kExamples / "evaluate_table_6_1_bevel.toml");
  EXPECT_EQ(bevel.design.needle.shape, needle::Shape::Bevel);
  EXPECT_DOUBLE_EQ(bevel.design.needle.base_diameter, 120e-6);
}

TEST(DesignConfig, Figure6_20ExamplesGiveTheFigureRanges) {
  for (const char* shape : {"cylinder", "cone", "bevel"}) {
    for (const bool hollow : {false, true}) {
      const std::string name = std::string("optimize_fig_6_20_") + shape + (hollow ? "_hollow" : "_solid") + ".toml";
      SCOPED_TRACE(name);
      const analysis::DesignSpace space = io::read_space_file(kExamples / name).space;
      EXPECT_EQ(needle::to_string(space.shape), shape);
      EXPECT_EQ(space.hollow, hollow);
      EXPECT_EQ(space.material.name, "silicon");
      EXPECT_DOUBLE_EQ(space.conditions.target_depth, 50e-6);
      EXPECT_EQ(space.spacing_factor, 3.0);
      EXPECT_EQ(space.needles_per_row.min, 5);
      EXPECT_EQ(space.needles_per_row.max, 25);
      EXPECT_DOUBLE_EQ(space.tip_diameter.max, 150e-6);
      EXPECT_DOUBLE_EQ(space.base_diameter.max, space.shape == needle::Shape::Cylinder ? 150e-6 : 300e-6);
      if (hollow) EXPECT_DOUBLE_EQ(space.bore_diameter.min, 20e-6);
      EXPECT_DOUBLE_EQ(space.width.step, 1000e-6);
      EXPECT_DOUBLE_EQ(space.length.min, 300e-6);
      // The file reproduces the library's own Fig 6.20 grid size.
      EXPECT_EQ(analysis::design_space_size(space),
                analysis::design_space_size(analysis::figure_6_20_space(space.shape, hollow)));
    }
  }
  const analysis::DesignSpace fine = io::read_space_file(kExamples / "optimize_certified_1um_cone_solid.toml").space;
  EXPECT_DOUBLE_EQ(fine.base_diameter.step, 1e-6);
  EXPECT_EQ(analysis::design_space_size(fine), 21ULL * 121 * 271 * 5001 * 201);
}

TEST(DesignConfig, InlineMaterialTissueAndInsertionOptions) {
  std::string text = replaced(replaced(kDesign, "shape = \"cone\"", "shape = \"cylinder\""),
                              "base_diameter = \"150 um\"\n", "");
  text = replaced(text, "material = \"silicon\"",
                              "material = { name = \"SU-8\", youngs_modulus = \"4 GPa\", allowable_stress = \"40 MPa\" }");
  text = replaced(text, "model = \"skin\"", "model = { alpha = \"0.0013 N\", tau = \"8.5 /mm\", small_tip_slope = \"0.05 /um\" }");
  text = replaced(text, "target_depth = \"50 um\"",
                  "angle = \"10 deg\"\napplication = \"brain\"\nbuckling_safety_factor = 2\nend_condition = "
                  "\"fixed-pinned\"\neffective_length = \"practical\"\njohnson = false");
  const io::DesignFile file = io::parse_design_toml(text, "inline.toml");
  EXPECT_EQ(file.design.material.name, "SU-8");
  EXPECT_DOUBLE_EQ(file.design.material.youngs_modulus, 4e9);
  EXPECT_FALSE(file.design.material.yield_strength.has_value());
  EXPECT_DOUBLE_EQ(*file.design.material.allowable_stress, 40e6);
  EXPECT_DOUBLE_EQ(file.conditions.tissue.alpha, 0.0013);
  EXPECT_DOUBLE_EQ(file.conditions.tissue.tau, 8500);
  EXPECT_DOUBLE_EQ(file.conditions.tissue.small_tip_slope, 5e4);
  EXPECT_NEAR(file.conditions.angle, 10 * M_PI / 180, 1e-15);
  EXPECT_DOUBLE_EQ(file.conditions.target_depth, 1e-3);
  EXPECT_EQ(file.options.buckling_safety_factor, 2.0);
  EXPECT_EQ(file.options.buckling.end_condition, analysis::EndCondition::FixedPinned);
  EXPECT_EQ(file.options.buckling.effective_length, analysis::EffectiveLengthValue::Practical);
  EXPECT_FALSE(file.options.buckling.johnson_for_short_columns);
}

// The uniform-column options (effective length factor K, Johnson's formula) do not apply to a cone's tapered column:
// an error naming the key, where they were silently ignored before.
TEST(DesignConfig, OptionsThatDoNotApplyToTheShapeAreErrors) {
  for (const char* option : {"effective_length = \"practical\"", "johnson = false"}) {
    const std::string text = replaced(kDesign, "target_depth = \"50 um\"", std::string("target_depth = \"50 um\"\n") + option);
    EXPECT_THAT([&] { io::parse_design_toml(text, "cone.toml"); },
                testing::ThrowsMessage<InvalidInput>(HasSubstr("cone.toml:17: key 'insertion.")));
    EXPECT_THAT([&] { io::parse_design_toml(text, "cone.toml"); },
                testing::ThrowsMessage<InvalidInput>(HasSubstr("does not apply to a cone")));
  }
}

TEST(DesignConfig, BadValuesNameFileLineAndKey) {
  const BadCase cases[] = {
      {"tip_diameter = \"30 um\"", "tip_diameter = \"-30 um\"", "bad.toml:3:", "'needle.tip_diameter'", "positive"},
      {"tip_diameter = \"30 um\"", "tip_diameter = \"0 um\"", "bad.toml:3:", "'needle.tip_diameter'", "positive"},
      {"length = \"500 um\"", "length = \"-1 mm\"", "bad.toml:5:", "'needle.length'", "positive"},
      {"width = \"1 cm\"", "width = \"0 cm\"", "bad.toml:10:", "'array.width'", "positive"},
      {"needles_per_row = 10", "needles_per_row = 0", "bad.toml:9:", "'array.needles_per_row'", ">= 1"},
      {"needles_per_row = 10", "needles_per_row = 2.5", "bad.toml:9:", "'array.needles_per_row'", "integer"},
      // D1 > D2 and the bore: the needle's own validation, placed at the key's line.
      {"tip_diameter = \"30 um\"", "tip_diameter = \"200 um\"", "bad.toml:3:", "'needle.tip_diameter'", "larger"},
      {"length = \"500 um\"", "bore_diameter = \"30 um\"\nlength = \"500 um\"", "bad.toml:5:", "'needle.bore_diameter'",
       "smaller"},
      {"length = \"500 um\"", "bore_diameter = \"200 um\"\nlength = \"500 um\"", "bad.toml:5:",
       "'needle.bore_diameter'", "smaller"},
      {"shape = \"cone\"", "shape = \"pyramid\"", "bad.toml:2:", "'needle.shape'", "\"cylinder\" | \"cone\" | \"bevel\""},
      {"material = \"silicon\"", "material = \"unobtainium\"", "bad.toml:6:", "'needle.material'", "silicon"},
      {"tip_diameter = \"30 um\"", "tip_diameter = \"30 furlongs\"", "bad.toml:3:", "'needle.tip_diameter'",
       "unknown unit"},
      {"tip_diameter = \"30 um\"", "tip_diameter = \"30 GPa\"", "bad.toml:3:", "'needle.tip_diameter'", "length"},
      {"tip_diameter = \"30 um\"", "tip_diameter = \"nan um\"", "bad.toml:3:", "'needle.tip_diameter'", "finite"},
      {"tip_diameter = \"30 um\"", "tip_diameter = 30", "bad.toml:3:", "'needle.tip_diameter'", "bare number"},
      {"tip_diameter = \"30 um\"", "tip_diameter = \"thirty\"", "bad.toml:3:", "'needle.tip_diameter'", "expected"},
      // Missing keys are reported at their table's line.
      {"length = \"500 um\"\n", "", "bad.toml:1:", "'needle.length'", "missing"},
      {"width = \"1 cm\"\n", "", "bad.toml:8:", "'array.width'", "missing"},
      {"[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n", "", "bad.toml:1:", "'array'", "missing"},
      {"shape = \"cone\"\n", "", "bad.toml:1:", "'needle.shape'", "missing"},
      // Unknown keys: typos are errors.
      {"tip_diameter = \"30 um\"", "tip_diam = \"30 um\"", "bad.toml:3:", "unknown key 'needle.tip_diam'",
       "tip_diameter"},
      {"[tissue]", "[tisue]", "bad.toml:12:", "unknown key 'tisue'", "tissue"},
      {"model = \"skin\"", "model = \"skin\"\nmodle = \"brain\"", "bad.toml:14:", "unknown key 'tissue.modle'", "model"},
      // Materials, tissue and insertion.
      {"material = \"silicon\"", "material = { youngs_modulus = \"-4 GPa\" }", "bad.toml:6:",
       "'needle.material.youngs_modulus'", "positive"},
      {"material = \"silicon\"", "material = { yield_strength = \"60 MPa\" }", "bad.toml:6:",
       "'needle.material.youngs_modulus'", "missing"},
      {"material = \"silicon\"", "material = { youngs_modulus = \"4 GPa\", poisson = 0.3 }", "bad.toml:6:",
       "unknown key 'needle.material.poisson'", "youngs_modulus"},
      {"material = \"silicon\"", "material = 4", "bad.toml:6:", "'needle.material'", "preset"},
      {"model = \"skin\"", "model = \"liver\"", "bad.toml:13:", "'tissue.model'", "skin"},
      {"model = \"skin\"", "model = { alpha = \"0.0183 N\" }", "bad.toml:13:", "'tissue.model.tau'", "missing"},
      {"model = \"skin\"", "model = { alpha = \"0.0183 N\", tau = \"6.25\" }", "bad.toml:13:", "'tissue.model.tau'",
       "no unit"},
      {"target_depth = \"50 um\"", "angle = \"90 deg\"", "bad.toml:16:", "'insertion.angle'", "[0, 90) deg"},
      {"target_depth = \"50 um\"", "target_depth = \"50 um\"\napplication = \"tattoo\"", "bad.toml:17:",
       "'insertion.application'", "target_depth"},
      {"target_depth = \"50 um\"", "application = \"cosmetic\"", "bad.toml:16:", "'insertion.application'",
       "transdermal"},
      {"target_depth = \"50 um\"", "end_condition = \"pinned\"", "bad.toml:16:", "'insertion.end_condition'",
       "fixed-free"},
      {"target_depth = \"50 um\"", "buckling_safety_factor = 0.5", "bad.toml:16:",
       "'insertion.buckling_safety_factor'", ">= 1"},
      {"target_depth = \"50 um\"", "johnson = \"yes\"", "bad.toml:16:", "'insertion.johnson'", "true or false"},
      {"shape = \"cone\"", "shape = \"cylinder\"", "bad.toml:1:", "'needle'", "cylinder"},
  };
  for (const BadCase& c : cases) expect_design_error(c);
}

TEST(DesignConfig, BadRangesNameFileLineAndKey) {
  const BadCase cases[] = {
      {"width = [\"5000 um\", \"10000 um\", \"1000 um\"]", "width = [\"10000 um\", \"5000 um\", \"1000 um\"]",
       "space.toml:10:", "'ranges.width'", "empty range"},
      {"length = [\"300 um\", \"500 um\", \"50 um\"]", "length = [\"300 um\", \"500 um\", \"0 um\"]", "space.toml:11:",
       "'ranges.length'", "step"},
      {"length = [\"300 um\", \"500 um\", \"50 um\"]", "length = [\"300 um\", \"500 um\", \"-50 um\"]",
       "space.toml:11:", "'ranges.length'", "step"},
      {"needles_per_row = [5, 25, 1]", "needles_per_row = [5, 25, 0]", "space.toml:7:", "'ranges.needles_per_row'",
       "step"},
      {"needles_per_row = [5, 25, 1]", "needles_per_row = [25, 5, 1]", "space.toml:7:", "'ranges.needles_per_row'",
       "empty range"},
      {"needles_per_row = [5, 25, 1]", "needles_per_row = [5, 25.5, 1]", "space.toml:7:",
       "'ranges.needles_per_row (max)'", "integer"},
      {"needles_per_row = [5, 25, 1]", "needles_per_row = [5, 25]", "space.toml:7:", "'ranges.needles_per_row'",
       "[min, max, step]"},
      {"tip_diameter = [\"30 um\", \"150 um\", \"10 um\"]", "tip_diameter = [30, 150, 10]", "space.toml:8:",
       "'ranges.tip_diameter (min)'", "bare number"},
      {"tip_diameter = [\"30 um\", \"150 um\", \"10 um\"]", "tip_diameter = [\"-30 um\", \"150 um\", \"10 um\"]",
       "space.toml:8:", "'ranges.tip_diameter'", "positive"},
      {"tip_diameter = [\"30 um\", \"150 um\", \"10 um\"]", "tip_diameter = [\"30 um\", \"nan um\", \"10 um\"]",
       "space.toml:8:", "'ranges.tip_diameter (max)'", "finite"},
      {"base_diameter = [\"30 um\", \"300 um\", \"10 um\"]\n", "", "space.toml:6:", "'ranges.base_diameter'",
       "missing"},
      {"length = [\"300 um\", \"500 um\", \"50 um\"]", "length = [\"300 um\", \"500 um\", \"50 um\"]\nbore_diameter = "
       "[\"20 um\", \"50 um\", \"10 um\"]", "space.toml:12:", "'ranges.bore_diameter'", "hollow"},
      {"hollow = false", "hollow = true", "space.toml:6:", "'ranges.bore_diameter'", "missing"},
      {"hollow = false", "hollow = \"no\"", "space.toml:2:", "'hollow'", "true or false"},
      {"width = [", "widht = [", "space.toml:10:", "unknown key 'ranges.widht'", "width"},
      {"shape = \"cone\"", "shape = \"cone\"\nshpe = \"bevel\"", "space.toml:2:", "unknown key 'shpe'", "shape"},
      {"material = \"silicon\"", "material = \"glass\"", "space.toml:3:", "'material'", "silicon"},
      {"target_depth = \"50 um\"", "target_depth = 50", "space.toml:4:", "'target_depth'", "bare number"},
      {"target_depth = \"50 um\"", "tissue = { alpha = \"-1 N\", tau = \"6.25 /mm\" }", "space.toml:4:",
       "'tissue.alpha'", "positive"},
  };
  for (const BadCase& c : cases) expect_space_error(c);
}

TEST(DesignConfig, CylinderSpaceTakesTheBaseFromTheTip) {
  std::string text = replaced(kSpace, "shape = \"cone\"", "shape = \"cylinder\"");
  text = replaced(text, "base_diameter = [\"30 um\", \"300 um\", \"10 um\"]\n", "");
  const analysis::DesignSpace space = io::parse_space_toml(text, "cylinder.toml").space;
  EXPECT_EQ(space.base_diameter.max, space.tip_diameter.max);
  // A different base range for a cylinder is a contradiction, not silently ignored.
  const std::string message = message_of<InvalidInput>([&] {
    io::parse_space_toml(replaced(kSpace, "shape = \"cone\"", "shape = \"cylinder\""), "cylinder.toml");
  });
  EXPECT_THAT(message, testing::StartsWith("cylinder.toml:9:"));
  EXPECT_THAT(message, HasSubstr("'ranges.base_diameter'"));
}

TEST(DesignConfig, SyntaxErrorsAndUnreadableFilesAreIoErrors) {
  const std::string syntax =
      message_of<IoError>([] { io::parse_design_toml(replaced(kDesign, "width = \"1 cm\"", "width = \"1 cm"), "bad.toml"); });
  EXPECT_THAT(syntax, testing::StartsWith("bad.toml:10:"));
  const std::string missing = message_of<IoError>([] { io::read_design_file("/nonexistent/design.toml"); });
  EXPECT_THAT(missing, HasSubstr("/nonexistent/design.toml"));
  const std::string directory = message_of<IoError>([] { io::read_space_file(kExamples); });
  EXPECT_THAT(directory, HasSubstr("directory"));
}
