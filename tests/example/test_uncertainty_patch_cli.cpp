// `needlekit uncertainty` on a patch case (examples/uncertainty_patch_neck.toml, fewer samples): the JSON keys of
// issue 15 with the per-needle probabilities, the files of --out (JSON, CSV, VTU, PNG), and bad input that exits with
// 2, one line naming the key, and nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/cli_run.hpp"
#include "../support/example_variants.hpp"

using needlekit::test::CliRun;
namespace test = needlekit::test;
using needlekit::test::kExamples;
using needlekit::test::file_text;
using testing::HasSubstr;

namespace {

class UncertaintyPatchCli : public needlekit::test::CliTest {
protected:
  UncertaintyPatchCli() : CliTest("uq-patch") {}
  // The example with `from` replaced by `to` (and 64 samples), its mesh path made absolute, as uq.toml.
  std::string example_with(const std::string& from, const std::string& to) const {
    test::Replacements replacements{
        {"mesh = \"../data/meshes/", "mesh = \"" + std::string(NEEDLEKIT_SOURCE_DIR) + "/data/meshes/"},
        {"samples = 1024", "samples = 64"}};
    if (!from.empty()) replacements.emplace_back(from, to);
    return test::write_example_variant("uncertainty_patch_neck.toml", replacements, dir_);
  }
};

}  // namespace

TEST_F(UncertaintyPatchCli, GivesPatchAndPerNeedleProbabilitiesAndTheMapFiles) {
  const CliRun r = run("uncertainty " + example_with("", "") + " --json --out result");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["samples"], 64);
  EXPECT_EQ(json["method"], "sobol");
  EXPECT_EQ(json["seed"], 2012);
  EXPECT_EQ(json["evaluations"], 64);
  EXPECT_EQ(json["status"], "ok");
  ASSERT_EQ(json["inputs"].size(), 5u);
  EXPECT_EQ(json["inputs"][0]["key"], "placement.offset_u");
  EXPECT_THAT(json["inputs"][2]["distribution"].get<std::string>(), HasSubstr("deg"));
  const auto& p = json["probabilities"];
  for (const char* event : {"all_succeed", "at_least_50_percent", "at_least_90_percent", "at_least_99_percent"}) {
    ASSERT_TRUE(p.contains(event)) << event;
    EXPECT_GE(p[event]["value"].get<double>(), p[event]["ci95"][0].get<double>()) << event;
    EXPECT_LE(p[event]["value"].get<double>(), p[event]["ci95"][1].get<double>()) << event;
  }
  // P(all) <= P(>= 99 %) <= P(>= 90 %) <= P(>= 50 %).
  EXPECT_LE(p["all_succeed"]["value"].get<double>(), p["at_least_99_percent"]["value"].get<double>());
  EXPECT_LE(p["at_least_99_percent"]["value"].get<double>(), p["at_least_90_percent"]["value"].get<double>());
  EXPECT_LE(p["at_least_90_percent"]["value"].get<double>(), p["at_least_50_percent"]["value"].get<double>());
  ASSERT_EQ(json["needles"].size(), 100u);
  double mean_success = 0;
  for (const auto& needle : json["needles"]) {
    ASSERT_EQ(needle["position_mm"].size(), 3u);
    for (const char* event : {"puncture", "buckling_failure", "bending_failure", "reaches_target", "success"}) {
      ASSERT_TRUE(needle["probabilities"].contains(event)) << event;
    }
    const double success = needle["probabilities"]["success"]["value"].get<double>();
    EXPECT_LE(success, needle["probabilities"]["puncture"]["value"].get<double>());
    mean_success += success / 100;
  }
  // The mean of the per-needle probabilities is the expected fraction of successes.
  EXPECT_NEAR(mean_success, json["success_fraction"]["mean"].get<double>(), 1e-12);
  EXPECT_EQ(json["needles"][99]["index"], 99);
  EXPECT_EQ(json["needles"][99]["i"], 9);
  EXPECT_EQ(json["needles"][99]["j"], 9);
  EXPECT_EQ(json["sobol"], nullptr);  // sobol_indices = false in the example
  EXPECT_EQ(nlohmann::json::parse(file_text(dir_ / "result" / "uncertainty.json")), json);
  EXPECT_THAT(file_text(dir_ / "result" / "needle_probabilities.csv"),
              HasSubstr("needle,i,j,x_mm,y_mm,z_mm,u_mm,v_mm,P_puncture,P_puncture_lo,P_puncture_hi,"));
  const std::string vtu = file_text(dir_ / "result" / "needle_probabilities.vtu");
  EXPECT_THAT(vtu, HasSubstr("Name=\"P_success\""));
  EXPECT_THAT(vtu, HasSubstr("NumberOfPoints=\"100\""));
  EXPECT_GT(std::filesystem::file_size(dir_ / "result" / "needle_probabilities.png"), 1000u);
}

TEST_F(UncertaintyPatchCli, TableShowsThePerNeedleMap) {
  const CliRun r = run("uncertainty " + example_with("sobol_indices = false", "sobol_indices = false") + " --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"64 samples (sobol, seed 2012)", "all_succeed", "P(success) per needle", "nominal fit:",
                           "uniform(min -3 mm, max 3 mm)"}) {
    EXPECT_THAT(r.out, HasSubstr(text));
  }
}

TEST_F(UncertaintyPatchCli, BadInputExitsTwoNamingTheKeyAndWritesNothing) {
  const std::pair<std::string, std::string> cases[] = {
      {R"(sd = "10 deg")", R"(sd = "-10 deg")"},
      {R"(min = "-3 mm", max = "3 mm" })", R"(min = "3 mm", max = "3 mm" })"},
      {R"("placement.offset_v" =)", R"("placement.offset_w" =)"},
      {R"("tissue.tau" =)", R"("array.width" =)"},
      {"samples = 64", "samples = 1"},
      {R"(min = "-3 mm", max = "3 mm" })", R"(min = "-3", max = "3 mm" })"},
  };
  const char* keys[] = {"placement.rotation", "placement.offset_u", "placement.offset_w", "array.width",
                        "sampling.samples", "placement.offset_u"};
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    test::expect_bad_input(run("uncertainty " + example_with(cases[i].first, cases[i].second) + " --out result"), keys[i],
                           dir_);
  }
}
