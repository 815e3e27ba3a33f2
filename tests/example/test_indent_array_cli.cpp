// `needlekit indent` on the 3 x 3 array example (examples/indent_array_3x3.toml): every needle of the array in the
// JSON with its forces and puncture, the needles the symmetry maps onto each other alike, the per-needle CSV, the
// ParaView point set and the map figure; bad array input exits with code 2 and writes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "../support/cli_run.hpp"

using needlekit::test::CliRun;
using needlekit::test::kExamples;
using needlekit::test::file_text;
using testing::HasSubstr;

namespace {

class IndentArrayCli : public needlekit::test::CliTest {
protected:
  IndentArrayCli() : CliTest("indent-array") {}
};

TEST_F(IndentArrayCli, ArrayExampleReportsEveryNeedle) {
  const CliRun r = run("indent " + kExamples + "indent_array_3x3.toml --json --out results");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  const nlohmann::json& needles = json["needles"];
  ASSERT_EQ(needles.size(), 9u);
  const std::size_t steps = json["force_N"].size();
  EXPECT_EQ(steps, 6u);
  double total = 0;
  for (const nlohmann::json& needle : needles) {
    for (const char* key : {"x_um", "y_um", "force_N", "punctured", "puncture_step"}) {
      EXPECT_TRUE(needle.contains(key)) << key;
    }
    ASSERT_EQ(needle["force_N"].size(), steps);
    total += needle["force_N"].back().get<double>();
  }
  // The needles' forces add up to the plate's; mirror images carry nearly the same force (a 30 um mesh: 5 %).
  EXPECT_NEAR(total / json["force_N"].back().get<double>(), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(needles[2]["x_um"].get<double>() - needles[1]["x_um"].get<double>(), 600.0);
  const auto last = [&](int k) { return needles[k]["force_N"].back().get<double>(); };
  EXPECT_NEAR(last(8) / last(0), 1.0, 0.05);
  EXPECT_NEAR(last(7) / last(1), 1.0, 0.05);
  // The centre needle, drawn down by eight neighbours, carries the least and punctures last (docs/arrays.md).
  for (int k : {0, 1, 2, 3, 5, 6, 7, 8}) {
    EXPECT_LT(last(4), last(k)) << k;
    EXPECT_GT(needles[4]["puncture_depth_um"].get<double>(), needles[k]["puncture_depth_um"].get<double>()) << k;
  }
  const nlohmann::json& array = json["array"];
  EXPECT_EQ(array["symmetry"], "none");
  EXPECT_EQ(array["plate_travel_um"].size(), steps);
  EXPECT_DOUBLE_EQ(array["punctured_fraction"].back().get<double>(), 1.0);
  EXPECT_GT(array["mean_penetrated_fraction"].get<double>(), 0.0);
  EXPECT_LT(array["mean_penetrated_fraction"].get<double>(), 0.25);  // 150 um of travel, 600 um needles

  const std::string csv = file_text(dir_ / "results/array_3x3_needles.csv");
  EXPECT_THAT(csv, HasSubstr("needle,row,column,x_um,y_um,punctured,puncture_step"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 10);
  EXPECT_THAT(file_text(dir_ / "results/array_3x3_needle_map.vtu"), HasSubstr("Name=\"inserted_depth_um\""));
  EXPECT_GT(std::filesystem::file_size(dir_ / "results/array_3x3_needle_map.png"), 10000u);
}

// `needlekit insert` on the same array: each needle's own curve, its FE indentation force until it punctures and its
// post-puncture (cutting) force of Alg 3.1 after, in the JSON and as CSV columns, summing to the array's force.
TEST_F(IndentArrayCli, InsertGivesEveryNeedleItsCuttingForceAfterItsPuncture) {
  std::string text = file_text(kExamples + "indent_array_3x3.toml");
  text = std::regex_replace(text, std::regex("continue_after_puncture = true"), "continue_after_puncture = false");
  text += "[post_puncture]\nstiffness = \"0.1 N/mm2\"\nscale = 0.168\nfinal_depth = \"400 um\"\nsamples = 40\n";
  std::ofstream(dir_ / "array.toml") << text;
  const CliRun r = run("insert array.toml --json --out results --no-plot");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  const nlohmann::json& curves = json["needle_curves"];
  ASSERT_EQ(curves.size(), 9u);
  ASSERT_EQ(json["punctures"].size(), 9u) << "every needle punctures within 150 um";
  const std::vector<double> depth = json["depth_um"], total = json["force_N"];
  const double last_puncture = json["punctures"].back()["displacement_um"];
  for (std::size_t s = 0; s < depth.size(); ++s) {
    double sum = 0;
    for (const nlohmann::json& curve : curves) sum += curve["force_N"][s].get<double>();
    EXPECT_NEAR(sum, total[s], 1e-10 * std::abs(total[s]) + 1e-15) << s;  // the JSON's 12 significant digits
    // Past the last puncture every needle cuts at the same depth (one needle shape, tips at one height): the same
    // cutting force, the array's ninth.
    if (depth[s] > last_puncture) {
      for (const nlohmann::json& curve : curves) {
        EXPECT_NEAR(curve["force_N"][s].get<double>(), total[s] / 9, 1e-10 * total[s]);
      }
    }
  }
  EXPECT_DOUBLE_EQ(curves[1]["x_um"].get<double>() - curves[0]["x_um"].get<double>(), 600.0);
  EXPECT_DOUBLE_EQ(curves[3]["y_um"].get<double>() - curves[0]["y_um"].get<double>(), 600.0);
  // The centre needle punctures last (docs/arrays.md), and each needle's puncture is one of the events.
  for (int k : {0, 1, 2, 3, 5, 6, 7, 8}) {
    EXPECT_GT(curves[4]["puncture_displacement_um"].get<double>(), curves[k]["puncture_displacement_um"].get<double>());
  }
  const std::string csv = file_text((dir_ / "results/array_3x3_insertion.csv").string());
  EXPECT_THAT(csv.substr(0, csv.find('\n')),
              testing::EndsWith("marker,needle_1_force_N,needle_2_force_N,needle_3_force_N,needle_4_force_N,"
                                "needle_5_force_N,needle_6_force_N,needle_7_force_N,needle_8_force_N,"
                                "needle_9_force_N"));
}

TEST_F(IndentArrayCli, BadArrayInputExitsWithCode2AndWritesNothing) {
  const std::string example = file_text(kExamples + "indent_array_3x3.toml");
  std::ofstream(dir_ / "pitch.toml") << std::regex_replace(example, std::regex("pitch = \"600 um\""), "pitch = \"200 um\"");
  const CliRun pitch = run("indent pitch.toml --out results");
  EXPECT_EQ(pitch.exit_code, 2);
  EXPECT_THAT(pitch.err, HasSubstr("pitch.toml:17: key 'array.pitch': 200 um is smaller than the needle's base"));
  std::ofstream(dir_ / "hexagonal.toml") << std::regex_replace(
      std::regex_replace(example, std::regex("layout = \"square\""), "layout = \"hexagonal\""),
      std::regex("symmetry = \"none\""), "symmetry = \"quarter\"");
  const CliRun hexagonal = run("indent hexagonal.toml --out results");
  EXPECT_EQ(hexagonal.exit_code, 2);
  EXPECT_THAT(hexagonal.err, HasSubstr("hexagonal.toml:20: key 'array.symmetry': \"quarter\" on a hexagonal array"));
  std::ofstream(dir_ / "small.toml") << std::regex_replace(example, std::regex("height = \"1000 um\""),
                                                           "height = \"1000 um\"\nwidth = \"1000 um\"");
  const CliRun small = run("indent small.toml --out results");
  EXPECT_EQ(small.exit_code, 2);
  EXPECT_THAT(small.err, HasSubstr("key 'tissue.width': 1000 um is too small for the array"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "results"));
}

}  // namespace
