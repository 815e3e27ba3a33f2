// Honest outputs on the command line: implausible scales are warnings on the terminal and in the result's notes,
// options that do not apply and an empty tissue case are errors, a mesh without attribution gets a warning instead of
// a silent omission, and values given with a unit come back with the user's digits.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "../support/cli_run.hpp"

using needlekit::test::CliRun;
using needlekit::test::file_text;
using needlekit::test::kExamples;
using testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

class HonestOutputs : public needlekit::test::CliTest {
protected:
  HonestOutputs() : CliTest("honest") {}
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  std::string example(const std::string& name) const { return file_text(kExamples + name); }
};

// `length = "400 mm"` (meant: 400 um): evaluated, with a warning naming the likely unit on stderr and in the notes.
TEST_F(HonestOutputs, ANeedleLengthInTheWrongUnitIsAWarningInNotesAndOnTheTerminal) {
  write("design.toml", std::regex_replace(example("evaluate_table_6_1_cone.toml"), std::regex("\"500 um\""),
                                          "\"400 mm\""));
  const CliRun r = run("evaluate design.toml --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("needlekit: warning: needle.length is 400 mm, outside the plausible 20 um to 5 mm"));
  EXPECT_THAT(r.err, HasSubstr("it would be 400 um"));
  const nlohmann::json json = nlohmann::json::parse(r.out);
  EXPECT_THAT(json["notes"].dump(), HasSubstr("needle.length is 400 mm"));
}

// The skull's arbitrary file units (15.8 mm each) declared as metres: a 13.9 m skull.
TEST_F(HonestOutputs, ABodyMeshInTheWrongUnitIsAWarning) {
  const CliRun r = run("surface " + std::string(NEEDLEKIT_SOURCE_DIR) + "/data/meshes/skull_yahoojapan_10k.obj --unit m --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warning: the body surface's largest extent (with --unit) is 13.91 m"));
  EXPECT_THAT(r.err, HasSubstr("outside the plausible 10 mm to 3 m"));
  EXPECT_EQ(nlohmann::json::parse(r.out)["notes"].size(), 1u);
  const CliRun right = run("surface " + std::string(NEEDLEKIT_SOURCE_DIR) +
                           "/data/meshes/skull_yahoojapan_10k.obj --unit '15.8 mm' --json");
  ASSERT_EQ(right.exit_code, 0) << right.err;
  EXPECT_TRUE(nlohmann::json::parse(right.out)["notes"].empty());
}

// A mesh whose folder has no README.md with its attribution: no ATTRIBUTION.md, and a warning that says so.
TEST_F(HonestOutputs, AMeshWithoutAttributionIsAWarning) {
  fs::copy_file(fs::path(NEEDLEKIT_SOURCE_DIR) / "data/meshes/skull_yahoojapan_10k.obj", dir_ / "skull.obj");
  write("patch.toml", std::regex_replace(std::regex_replace(example("patch_skull.toml"),
                                                            std::regex("\"../data/meshes/skull_yahoojapan_100k.obj\""),
                                                            "\"skull.obj\""),
                                         std::regex("center_vertex = 23319"), "center_vertex = 3627"));
  const CliRun r = run("patch patch.toml --out out --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warning: no licence or attribution found for"));
  EXPECT_FALSE(fs::exists(dir_ / "out/ATTRIBUTION.md"));
  EXPECT_THAT(nlohmann::json::parse(file_text(dir_ / "out/summary.json"))["notes"].dump(),
              HasSubstr("no licence or attribution"));
}

// The shipped skull: ATTRIBUTION.md holds its own entry (not the other meshes') and where the licences are.
TEST_F(HonestOutputs, AttributionNamesTheMeshsOwnEntry) {
  const CliRun r = run("patch " + kExamples + "patch_skull.toml --out out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string attribution = file_text(dir_ / "out/ATTRIBUTION.md");
  EXPECT_THAT(attribution, HasSubstr("Skull by YahooJAPAN"));
  EXPECT_THAT(attribution, HasSubstr("CC BY 3.0"));
  EXPECT_THAT(attribution, HasSubstr("licenses/"));
  EXPECT_THAT(attribution, testing::Not(HasSubstr("Visible Human")));
}

TEST_F(HonestOutputs, ValuesGivenWithAUnitComeBackWithTheUsersDigits) {
  write("design.toml", std::regex_replace(example("evaluate_table_6_1_cone.toml"), std::regex("\"150 um\""),
                                          "\"200 um\""));
  const CliRun r = run("evaluate design.toml --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["base_diameter_um"].get<double>(), 200.0);
  EXPECT_THAT(r.out, testing::Not(HasSubstr("99999999")));
}

TEST_F(HonestOutputs, AnOptionThatDoesNotApplyIsAnError) {
  write("design.toml", example("evaluate_table_6_1_cone.toml") + "effective_length = \"practical\"\n");
  const CliRun r = run("evaluate design.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("key 'insertion.effective_length': does not apply to a cone"));
}

TEST_F(HonestOutputs, AnEmptyTissueCaseIsAnErrorNamingWhatIsMissing) {
  write("empty.toml", "");
  const CliRun r = run("tissue-mesh empty.toml --out out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("empty.toml:1: missing table [tissue]"));
  EXPECT_FALSE(fs::exists(dir_ / "out/tissue.vtu"));
}

// tissue-mesh on an array case meshes [tissue] and [mesh] only: it says so rather than ignore [array] silently.
TEST_F(HonestOutputs, TissueMeshWarnsThatItDoesNotMeshAnArraysBlock) {
  write("array.toml", "[tissue]\npreset = \"silicone-0.2mpa\"\n[mesh]\nsize_at_tip = \"150 um\"\n"
                      "size_far = \"600 um\"\n[array]\nrows = 2\ncolumns = 2\npitch = \"600 um\"\n");
  const CliRun r = run("tissue-mesh array.toml --out out");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("needlekit: warning: array.toml:6: table [array]: not read here"));
  EXPECT_TRUE(fs::exists(dir_ / "out/tissue.vtu"));
}

// An 800 um depth into a 500 um block: refused before any meshing, naming the key.
TEST_F(HonestOutputs, ADepthThroughTheBlockIsRefused) {
  write("deep.toml", "[needle]\nshape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"1 mm\"\n[tissue]\n"
                     "[[tissue.layers]]\nname = \"gel\"\nthickness = \"500 um\"\nyoungs_modulus = \"0.2 MPa\"\n"
                     "poisson_ratio = 0.45\n[loading]\ndepth = \"800 um\"\n");
  const CliRun r = run("indent deep.toml --out out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("key 'loading.depth': 800 um reaches through the 500 um high tissue block"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace
