// `needlekit uncertainty` on an FE case (examples/uncertainty_fe_puncture.toml): the surrogate's stated validation
// error, the probability and distributions from it, the FE runs' CSV, and bad input that exits with 2 naming the key
// before any FE run, with nothing written.
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

class UncertaintyFeCli : public needlekit::test::CliTest {
protected:
  UncertaintyFeCli() : CliTest("uq-fe") {}
  // The example with `from` replaced by `to` and its case path made absolute, as uq.toml.
  std::string example_with(const std::string& from, const std::string& to) const {
    test::Replacements replacements{{"case = \"", "case = \"" + kExamples}};
    if (!from.empty()) replacements.emplace_back(from, to);
    return test::write_example_variant("uncertainty_fe_puncture.toml", replacements, dir_);
  }
};

}  // namespace

TEST_F(UncertaintyFeCli, StatesTheValidationErrorAndSamplesTheSurrogate) {
  const CliRun r = run("uncertainty " + example_with("samples = 4096", "samples = 1024") + " --json --out result");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["samples"], 1024);
  const auto& s = json["surrogate"];
  EXPECT_EQ(s["terms"], 6);
  EXPECT_EQ(s["fe_runs"], 17);
  EXPECT_EQ(s["design_runs"], 12);
  EXPECT_EQ(s["validation_runs"], 4);
  const double depth_error = s["validation_error"]["puncture_depth"]["max_relative"].get<double>();
  EXPECT_GT(depth_error, 0.0);  // the FE depth is interpolated between load steps: no polynomial is exact
  EXPECT_LT(depth_error, 0.01);
  EXPECT_LE(s["validation_error"]["puncture_force"]["rms_relative"].get<double>(),
            s["validation_error"]["puncture_force"]["max_relative"].get<double>());
  EXPECT_EQ(json["depth_limit_um"], 100.0);
  const auto& p = json["probabilities"]["punctures_before_depth"];
  EXPECT_GT(p["value"].get<double>(), 0.7);
  EXPECT_LT(p["value"].get<double>(), 0.9);
  EXPECT_LE(p["ci95"][0].get<double>(), p["value"].get<double>());
  const auto& depth = json["puncture_depth_um"];
  EXPECT_LT(depth["q05"].get<double>(), json["nominal"]["puncture_depth_um"].get<double>());
  EXPECT_GT(depth["q95"].get<double>(), json["nominal"]["puncture_depth_um"].get<double>());
  EXPECT_TRUE(json["sobol"]["total"].contains("puncture.critical_pressure"));
  EXPECT_EQ(nlohmann::json::parse(file_text(dir_ / "result" / "uncertainty.json")), json);
  const std::string csv = file_text(dir_ / "result" / "fe_runs.csv");
  EXPECT_THAT(csv, HasSubstr("role,tissue.layers.0.youngs_modulus_MPa,puncture.critical_pressure_MPa,status,"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 18);
}

TEST_F(UncertaintyFeCli, BadInputExitsTwoNamingTheKeyAndWritesNothing) {
  const std::pair<std::string, std::string> cases[] = {
      {"sigma_log = 0.25", "sigma_log = -0.25"},
      {"tissue.layers.0.youngs_modulus", "tissue.layers.2.youngs_modulus"},
      {"tissue.layers.0.youngs_modulus", "tissue.layers.0.poisson_ratio"},
      {"validation_runs = 4", "validation_runs = 0"},
      {"depth_limit = \"100 um\"", "depth_limit = 100"},
      {"samples = 4096", "samples = 1"},
  };
  const char* keys[] = {"tissue.layers.0.youngs_modulus", "layer 2 does not exist", "tissue.layers.0.poisson_ratio",
                        "surrogate.validation_runs", "surrogate.depth_limit", "sampling.samples"};
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    test::expect_bad_input(run("uncertainty " + example_with(cases[i].first, cases[i].second) + " --out result"), keys[i],
                           dir_);
  }
}
