// `needlekit uncertainty` on examples/uncertainty_cone_su8.toml: the JSON keys of issue 15, probabilities that
// are consistent with each other and with the deterministic evaluation, output files with --out, and bad input that
// exits with 2, one line naming the key, and no output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/cli_run.hpp"

using needlekit::test::CliRun;
using needlekit::test::kExamples;
using needlekit::test::file_text;
using testing::HasSubstr;

namespace {

class UncertaintyCli : public needlekit::test::CliTest {
protected:
  UncertaintyCli() : CliTest("uq") {}
  std::string example_with(const std::string& from, const std::string& to) const {
    std::string text = file_text(kExamples + "uncertainty_cone_su8.toml");
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    std::ofstream(dir_ / "uq.toml") << text;
    return "uq.toml";
  }
};

}  // namespace

TEST_F(UncertaintyCli, ExampleGivesProbabilitiesIndexDistributionAndSobolIndices) {
  const CliRun r = run("uncertainty " + kExamples + "uncertainty_cone_su8.toml --json --out result");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["samples"], 4096);
  EXPECT_EQ(json["method"], "sobol");
  EXPECT_EQ(json["seed"], 2012);
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["reason"], "");
  const auto& p = json["probabilities"];
  for (const char* event : {"puncture", "buckling_failure", "bending_failure", "reaches_target", "success"}) {
    ASSERT_TRUE(p.contains(event)) << event;
    const double value = p[event]["value"].get<double>();
    EXPECT_GE(value, p[event]["ci95"][0].get<double>()) << event;
    EXPECT_LE(value, p[event]["ci95"][1].get<double>()) << event;
  }
  // success = punctures, neither fails, reaches the target.
  const double success = p["success"]["value"].get<double>();
  EXPECT_LE(success, p["puncture"]["value"].get<double>());
  EXPECT_LE(success, p["reaches_target"]["value"].get<double>());
  EXPECT_LE(success, 1 - p["buckling_failure"]["value"].get<double>());
  EXPECT_LE(success, 1 - p["bending_failure"]["value"].get<double>());
  // The cone works on most skin, but a tenth of the insertions bend it: the lateral force at up to 20 deg reaches
  // the polymer's critical bending load (the nominal design, at 10 deg, works).
  EXPECT_GT(success, 0.8);
  EXPECT_LT(success, 0.9);
  EXPECT_GT(p["bending_failure"]["value"].get<double>(), 0.1);
  EXPECT_EQ(p["buckling_failure"]["value"].get<double>(), 0.0);
  const auto& index = json["performance_index_per_um"];
  EXPECT_LE(index["q05"].get<double>(), index["q50"].get<double>());
  EXPECT_LE(index["q50"].get<double>(), index["q95"].get<double>());
  EXPECT_NEAR(json["nominal"]["performance_index_per_um"].get<double>(), 2.041e-4, 1e-7);
  EXPECT_NEAR(index["q50"].get<double>(), 2.0e-4, 0.1e-4);
  EXPECT_EQ(index["q05"].get<double>(), 0.0);  // more than 5 % of the insertions fail: index 0
  // The Sobol' indices are keyed by the inputs as written. The tip diameter dominates the index (it sets the tip
  // area, hence the puncture force, the deformation d and the bending load, Fig 6.18); the modulus does not
  // matter (the cone never buckles); the angle acts through the bending failures (total >> first order).
  const auto& first = json["sobol"]["first"];
  const auto& total = json["sobol"]["total"];
  double first_sum = 0;
  for (const char* key : {"tissue.alpha", "tissue.tau", "needle.tip_diameter", "needle.length",
                          "needle.material.youngs_modulus", "insertion.angle"}) {
    ASSERT_TRUE(first.contains(key)) << key;
    EXPECT_LE(first[key].get<double>(), total[key].get<double>() + 0.02) << key;
    first_sum += first[key].get<double>();
  }
  EXPECT_LT(first_sum, 1.05);
  EXPECT_GT(first["needle.tip_diameter"].get<double>(), 0.4);
  EXPECT_LT(total["needle.material.youngs_modulus"].get<double>(), 0.01);
  EXPECT_GT(total["insertion.angle"].get<double>(), 2 * first["insertion.angle"].get<double>());
  EXPECT_TRUE(json["one_at_a_time"].contains("needle.tip_diameter"));
  // --out holds the same object and the tables.
  EXPECT_EQ(nlohmann::json::parse(file_text(dir_ / "result" / "uncertainty.json")), json);
  EXPECT_THAT(file_text(dir_ / "result" / "performance_index_histogram.csv"),
              HasSubstr("performance_index_low_per_um,performance_index_high_per_um,count\n"));
  EXPECT_THAT(file_text(dir_ / "result" / "sobol_indices.csv"), HasSubstr("performance_index,needle.tip_diameter,"));
}

TEST_F(UncertaintyCli, TableNamesEventsAndUnits) {
  const CliRun r = run("uncertainty " + example_with("samples = 4096", "samples = 1024"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"1024 samples (sobol, seed 2012)", "success", "buckling_failure", "95 % interval",
                           "performance index (1/um)", "S_i", "one at a time (Fig 6.18)", "lognormal(median 0.0183 N", "bending_failure"}) {
    EXPECT_THAT(r.out, HasSubstr(text));
  }
}

TEST_F(UncertaintyCli, BadInputExitsTwoNamingTheKeyAndWritesNothing) {
  const std::pair<std::string, std::string> cases[] = {
      {R"(sd = "3 um")", R"(sd = "-3 um")"},
      {R"(min = "0 deg", max = "20 deg")", R"(min = "20 deg", max = "20 deg")"},
      {R"("needle.length" =)", R"("needle.lenght" =)"},
      {R"(sd = "3 um")", R"(sd = "30 um")"},  // 1 % of the tip diameters <= 0
      {"samples = 4096", "samples = 1"},
      {R"(distribution = "uniform")", R"(distribution = "beta")"},
  };
  const char* keys[] = {"needle.tip_diameter", "insertion.angle", "needle.lenght", "needle.tip_diameter",
                        "sampling.samples", "insertion.angle"};
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    const CliRun r = run("uncertainty " + example_with(cases[i].first, cases[i].second) + " --out result");
    EXPECT_EQ(r.exit_code, 2) << cases[i].second;
    EXPECT_THAT(r.err, HasSubstr(keys[i])) << r.err;
    EXPECT_THAT(r.err, HasSubstr("uq.toml:")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_FALSE(std::filesystem::exists(dir_ / "result"));
  }
}

TEST_F(UncertaintyCli, RobustOptimizeFindsTheBestDesignThatMeetsTheLevelAndItsCost) {
  const CliRun r = run("optimize " + kExamples + "optimize_robust_cone_su8.toml --json --top 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  const auto& robust = json["robust"];
  EXPECT_EQ(robust["status"], "found");
  EXPECT_EQ(robust["min_success_probability"], 0.99);
  EXPECT_GE(robust["design"]["success_probability"].get<double>(), 0.99);
  // The deterministic optimum is the nominal ranking's best, and it is not robust: it bends at an angle.
  EXPECT_EQ(robust["nominal_optimum"]["performance_index_per_um"], json["best"]["performance_index_per_um"]);
  EXPECT_LT(robust["nominal_optimum"]["success_probability"].get<double>(), 0.5);
  const double cost = robust["index_cost_per_um"].get<double>();
  EXPECT_NEAR(cost, json["best"]["performance_index_per_um"].get<double>() -
                        robust["design"]["performance_index_per_um"].get<double>(), 1e-15);
  EXPECT_GT(robust["index_cost_percent"].get<double>(), 10.0);
  EXPECT_GT(robust["candidates_checked"].get<int>(), 1);
  EXPECT_EQ(json["top"].size(), 3u);
}

TEST_F(UncertaintyCli, RobustOptimizeRefusesADesignVariableWithAMeanAndCertified) {
  std::string text = file_text(kExamples + "optimize_robust_cone_su8.toml");
  text.insert(text.find("[sampling]"), "\"needle.length\" = { distribution = \"normal\", mean = \"500 um\", sd = \"5 um\" }\n");
  std::ofstream(dir_ / "space.toml") << text;
  CliRun r = run("optimize space.toml --out result.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("key 'uncertain.\"needle.length\"': a design variable's spread is centred"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "result.json"));
  r = run("optimize " + kExamples + "optimize_robust_cone_su8.toml --certified");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--certified does not apply with min_success_probability"));
}

TEST_F(UncertaintyCli, NoPlotOnADesignFileIsAnError) {
  const CliRun r = run("uncertainty " + kExamples + "uncertainty_cone_su8.toml --no-plot --out result");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--no-plot applies to patch cases only"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "result"));
}
