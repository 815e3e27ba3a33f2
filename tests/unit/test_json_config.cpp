// Design, design-space, uncertainty and patch files given as JSON (io/json_config.hpp, the `needlekit serve` API): they
// read to the same values as their TOML files, every bad input gives the TOML reader's message for the same key (after
// the "FILE:LINE:" location), so that the API answers with the CLI's words, and a patch case's mesh is only ever a name
// from the caller's list.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/json_config.hpp"
#include "needlekit/io/uncertainty_config.hpp"

using namespace needlekit;
using testing::HasSubstr;
using testing::StartsWith;

namespace {

const std::filesystem::path kCone = std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "examples" /
                                    "evaluate_table_6_1_cone.toml";

// examples/evaluate_table_6_1_cone.toml as JSON.
constexpr std::string_view kDesignJson = R"({
  "needle": {"shape": "cone", "tip_diameter": "30 um", "base_diameter": "150 um", "length": "500 um",
             "material": "silicon"},
  "array": {"needles_per_row": 10, "width": "1 cm"},
  "tissue": {"model": "skin"},
  "insertion": {"angle": "0 deg", "target_depth": "50 um"}
})";

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The message after its "FILE:LINE: " location.
std::string after_location(const std::string& message) {
  const std::size_t colon = message.find(": ");
  return colon == std::string::npos ? message : message.substr(colon + 2);
}

template <class Read>
std::string message_of(Read&& read) {
  try {
    read();
  } catch (const InvalidInput& error) {
    return error.what();
  } catch (const IoError& error) {
    return std::string("IoError: ") + error.what();
  }
  return "no error";
}

// One bad input, as TOML and as JSON.
struct BadCase {
  const char* toml;
  const char* json;
  const char* expected;  // a part of the message
};

const BadCase kBadCases[] = {
    {"[needle]\nshape = \"cone\"\ntip_diameter = \"-30 um\"\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
     "material = \"silicon\"\n[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n",
     R"({"needle": {"shape": "cone", "tip_diameter": "-30 um", "base_diameter": "150 um", "length": "500 um",
         "material": "silicon"}, "array": {"needles_per_row": 10, "width": "1 cm"}})",
     "key 'needle.tip_diameter': '-30 um' is not positive"},
    {"[needle]\nshape = \"cone\"\ntip_diameter = 30\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
     "material = \"silicon\"\n[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n",
     R"({"needle": {"shape": "cone", "tip_diameter": 30, "base_diameter": "150 um", "length": "500 um",
         "material": "silicon"}, "array": {"needles_per_row": 10, "width": "1 cm"}})",
     "key 'needle.tip_diameter': 30 is a bare number without a unit"},
    {"[needle]\nshape = \"cone\"\ntip_diameter = \"30 um\"\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
     "material = \"silicon\"\ncolour = \"red\"\n[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n",
     R"({"needle": {"shape": "cone", "tip_diameter": "30 um", "base_diameter": "150 um", "length": "500 um",
         "material": "silicon", "colour": "red"}, "array": {"needles_per_row": 10, "width": "1 cm"}})",
     "unknown key 'needle.colour'"},
    {"[needle]\nshape = \"cone\"\ntip_diameter = \"30 um\"\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
     "material = \"silicon\"\n[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n[insertion]\nangle = \"95 deg\"\n",
     R"({"needle": {"shape": "cone", "tip_diameter": "30 um", "base_diameter": "150 um", "length": "500 um",
         "material": "silicon"}, "array": {"needles_per_row": 10, "width": "1 cm"}, "insertion": {"angle": "95 deg"}})",
     "key 'insertion.angle': '95 deg' is out of range"},
    {"[needle]\nshape = \"wedge\"\ntip_diameter = \"30 um\"\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
     "material = \"silicon\"\n[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n",
     R"({"needle": {"shape": "wedge", "tip_diameter": "30 um", "base_diameter": "150 um", "length": "500 um",
         "material": "silicon"}, "array": {"needles_per_row": 10, "width": "1 cm"}})",
     "key 'needle.shape': unknown value 'wedge'"},
    {"[needle]\nshape = \"cone\"\ntip_diameter = \"30 um\"\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
     "material = \"silicon\"\n[array]\nneedles_per_row = 0\nwidth = \"1 cm\"\n",
     R"({"needle": {"shape": "cone", "tip_diameter": "30 um", "base_diameter": "150 um", "length": "500 um",
         "material": "silicon"}, "array": {"needles_per_row": 0, "width": "1 cm"}})",
     "key 'array.needles_per_row': 0 is out of range"},
    {"[needle]\nshape = \"cone\"\ntip_diameter = \"30 um\"\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
     "material = \"silicon\"\n",
     R"({"needle": {"shape": "cone", "tip_diameter": "30 um", "base_diameter": "150 um", "length": "500 um",
         "material": "silicon"}})",
     "key 'array': missing"},
};

}  // namespace

TEST(JsonConfig, ADesignReadsToTheSameValuesAsItsTomlFile) {
  const io::DesignFile from_toml = io::read_design_file(kCone);
  const io::DesignFile from_json = io::parse_design_json(kDesignJson, "design.json");
  EXPECT_EQ(from_json.design.needle.shape, from_toml.design.needle.shape);
  EXPECT_DOUBLE_EQ(from_json.design.needle.tip_diameter, 30e-6);
  EXPECT_DOUBLE_EQ(from_json.design.needle.base_diameter, from_toml.design.needle.base_diameter);
  EXPECT_DOUBLE_EQ(from_json.design.needle.length, from_toml.design.needle.length);
  EXPECT_EQ(from_json.design.material.name, from_toml.design.material.name);
  EXPECT_EQ(from_json.design.needles_per_row, 10);
  EXPECT_DOUBLE_EQ(from_json.design.width, 1e-2);
  EXPECT_DOUBLE_EQ(from_json.options.spacing_factor, from_toml.options.spacing_factor);
  EXPECT_DOUBLE_EQ(from_json.conditions.angle, from_toml.conditions.angle);
  EXPECT_DOUBLE_EQ(from_json.conditions.target_depth, 50e-6);
  EXPECT_EQ(from_json.conditions.tissue.name, "skin");
}

TEST(JsonConfig, EveryBadInputGivesTheTomlReadersMessage) {
  for (const BadCase& c : kBadCases) {
    const std::string toml = message_of([&] { io::parse_design_toml(c.toml, "design.toml"); });
    const std::string json = message_of([&] { io::parse_design_json(c.json, "design.json"); });
    EXPECT_THAT(toml, HasSubstr(c.expected));
    EXPECT_THAT(json, StartsWith("design.json:1: "));
    EXPECT_EQ(after_location(json), after_location(toml)) << c.expected;
  }
}

TEST(JsonConfig, OptionsThatDoNotApplyAreRefusedAsInToml) {
  const std::string toml =
      message_of([&] { io::parse_design_toml(file_text(kCone) + "johnson = false\n", "design.toml"); });
  const std::string json = message_of([&] {
    io::parse_design_json(R"({"needle": {"shape": "cone", "tip_diameter": "30 um", "base_diameter": "150 um",
        "length": "500 um", "material": "silicon"}, "array": {"needles_per_row": 10, "width": "1 cm"},
        "insertion": {"johnson": false}})", "design.json");
  });
  EXPECT_THAT(json, HasSubstr("key 'insertion.johnson': does not apply to a cone"));
  EXPECT_EQ(after_location(json), after_location(toml));
}

TEST(JsonConfig, MalformedJsonNullsAndNonObjectsAreBadInput) {
  EXPECT_THAT(message_of([] { io::parse_design_json(R"({"needle": )", "design.json"); }),
              HasSubstr("IoError: design.json:1: invalid JSON"));
  EXPECT_THAT(message_of([] { io::parse_design_json("[1, 2]", "design.json"); }),
              HasSubstr("the JSON is array, expected an object"));
  EXPECT_THAT(message_of([] { io::parse_design_json(R"({"needle": {"length": null}})", "design.json"); }),
              HasSubstr("design.json:1: key 'needle.length': null is not a value"));
  EXPECT_THAT(message_of([] { io::parse_design_json(R"({"array": {"needles_per_row": 18446744073709551615}})",
                                                    "design.json"); }),
              HasSubstr("key 'array.needles_per_row': 18446744073709551615 is out of range"));
}

TEST(JsonConfig, SpaceAndUncertaintyFilesReadAsTheirTomlFiles) {
  const io::SpaceFile space = io::parse_space_json(R"({"shape": "cone", "hollow": false, "material": "silicon",
      "target_depth": "50 um", "ranges": {"needles_per_row": [5, 25, 1], "tip_diameter": ["30 um", "150 um", "10 um"],
      "base_diameter": ["30 um", "300 um", "10 um"], "width": ["5000 um", "10000 um", "1000 um"],
      "length": ["300 um", "500 um", "50 um"]}})", "space.json");
  EXPECT_DOUBLE_EQ(space.space.tip_diameter.step, 10e-6);
  EXPECT_DOUBLE_EQ(space.space.needles_per_row.max, 25);
  EXPECT_FALSE(space.robust.has_value());

  const io::UncertaintyFile uq = io::parse_uncertainty_json(R"({"needle": {"shape": "cone", "tip_diameter": "70 um",
      "base_diameter": "200 um", "length": "600 um", "material": "su-8"}, "array": {"needles_per_row": 10,
      "width": "1 cm"}, "insertion": {"angle": "10 deg"},
      "uncertain": {"tissue.alpha": {"distribution": "lognormal", "sigma_log": 0.3},
                    "needle.tip_diameter": {"distribution": "normal", "sd": "3 um"}},
      "sampling": {"samples": 256, "seed": 7}})", "uncertainty.json");
  ASSERT_EQ(uq.inputs.size(), 2u);
  EXPECT_EQ(uq.sampling.samples, 256u);
  EXPECT_EQ(uq.sampling.seed, 7u);
  EXPECT_THAT(message_of([] {
                io::parse_uncertainty_json(R"({"needle": {"shape": "cone", "tip_diameter": "70 um",
                    "base_diameter": "200 um", "length": "600 um", "material": "su-8"}, "array": {"needles_per_row": 10,
                    "width": "1 cm"}, "uncertain": {"needle.tip_diameter": {"distribution": "normal", "sd": "-3 um"}}})",
                                           "uncertainty.json");
              }),
              HasSubstr("needle.tip_diameter"));
}

TEST(JsonConfig, APatchCaseMeshIsANameFromTheListNeverAPath) {
  const std::filesystem::path meshes = std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "data" / "meshes";
  const std::map<std::string, std::filesystem::path> offered{
      {"skull_yahoojapan_10k.obj", meshes / "skull_yahoojapan_10k.obj"}};
  const auto case_with = [](std::string_view mesh) {
    return fmt::format(R"({{"surface": {{"mesh": "{}", "unit": "15.8 mm", "center_vertex": 3627}},
        "patch": {{"kind": "rigid", "size": "10 mm", "needles_per_row": 10, "spring_constant": "1 N/mm"}},
        "needle": {{"shape": "cylinder", "tip_diameter": "70 um", "length": "400 um", "material": "su-8"}}}})",
                       mesh);
  };
  const io::PatchCase c = io::parse_patch_case_json(case_with("skull_yahoojapan_10k.obj"), "patch.json", offered);
  EXPECT_EQ(c.mesh, meshes / "skull_yahoojapan_10k.obj");
  EXPECT_DOUBLE_EQ(c.mesh_unit, 0.0158);
  for (std::string_view bad : {"../../etc/passwd", "/etc/passwd", "skull_yahoojapan_10k.obj/../README.md", "README.md",
                               ""}) {
    EXPECT_THAT(message_of([&] { io::parse_patch_case_json(case_with(bad), "patch.json", offered); }),
                HasSubstr(fmt::format("patch.json:1: key 'surface.mesh': '{}' is not one of the meshes offered, "
                                      "expected one of: skull_yahoojapan_10k.obj",
                                      bad)))
        << bad;
  }
  // A name whose file is not that name (a caller's mistake) is refused too.
  const std::map<std::string, std::filesystem::path> wrong{{"a.obj", meshes / "skull_yahoojapan_10k.obj"}};
  EXPECT_THAT(message_of([&] { io::parse_patch_case_json(case_with("a.obj"), "patch.json", wrong); }),
              HasSubstr("is not one of the meshes offered"));
}
