// `needlekit calibrate`: an analytic calibration end to end (alpha and tau of the skin model from deformations of four
// needles: exit 0, the JSON keys of issue 13, the files, a calibrated case that reads back), exit 3 with results kept
// when the iterations run out, and bad input (exit 2, one line, no output files).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../support/cli_run.hpp"

using needlekit::test::file_text;
using needlekit::test::run_cli;
using testing::HasSubstr;

namespace {

namespace fs = std::filesystem;

void put(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// Four cylinders; d from Eq 4.3 with the skin model (alpha = 0.0183 N, tau = 6.25 /mm): d = ln(F(A)/alpha)/tau.
fs::path analytic_problem(const std::string& name, int max_iterations) {
  const fs::path dir = needlekit::test::fresh_directory("calibrate-" + name);
  std::string experiments;
  for (double tip : {80.0, 100.0, 120.0, 150.0}) {
    put(dir / fmt::format("tip_{}.toml", tip),
        fmt::format("[needle]\nshape = \"cylinder\"\ntip_diameter = \"{} um\"\nlength = \"600 um\"\nmaterial = "
                    "\"silicon\"\n[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n[tissue]\nmodel = {{ alpha = "
                    "\"0.03 N\", tau = \"4 /mm\" }}\n",
                    tip));
    const double area = M_PI / 4 * tip * tip;
    const double d_um = std::log((0.00019 * area - 0.66) / 0.0183) / 6.25e-3;
    experiments += fmt::format("[[experiments]]\nname = \"tip {0}\"\ncase = \"tip_{0}.toml\"\npuncture = {{ depth = "
                               "\"{1:.17g} um\" }}\n",
                               tip, d_um);
  }
  put(dir / "fit.toml", fmt::format("name = \"skin\"\n[solver]\nmax_iterations = {}\n[[parameters]]\npath = "
                                    "\"tissue.model.alpha\"\ninitial = \"0.03 N\"\nbounds = [\"0.001 N\", \"0.1 N\"]\n"
                                    "[[parameters]]\npath = \"tissue.model.tau\"\ninitial = \"4 /mm\"\nbounds = "
                                    "[\"1 /mm\", \"20 /mm\"]\n{}",
                                    max_iterations, experiments));
  return dir;
}

TEST(CalibrateCli, AnalyticAlphaAndTau) {
  const fs::path dir = analytic_problem("analytic", 50);
  const auto run = run_cli(dir, "calibrate fit.toml --json --out out --write-case calibrated.toml");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  for (const char* key : {"status", "reason", "iterations", "rms_relative", "parameters", "experiments", "correlation"})
    EXPECT_TRUE(json.contains(key)) << key;
  EXPECT_EQ(json["status"], "converged");
  const auto& alpha = json["parameters"]["tissue.model.alpha"];
  EXPECT_NEAR(alpha["value"].get<double>(), 0.0183, 1e-8);
  EXPECT_EQ(alpha["unit"], "N");
  EXPECT_EQ(json["parameters"]["tissue.model.tau"]["unit"], "1/m");
  EXPECT_NEAR(json["parameters"]["tissue.model.tau"]["value"].get<double>(), 6250, 1e-3);
  EXPECT_EQ(json["parameters"]["tissue.model.tau"]["as_given"], "6.25 /mm");
  EXPECT_EQ(json["parameters"]["tissue.model.alpha"]["ci95"].size(), 2u);
  ASSERT_EQ(json["experiments"].size(), 4u);
  for (const char* key : {"name", "rms_relative", "puncture_depth_um", "puncture_force_N"})
    EXPECT_TRUE(json["experiments"][0].contains(key)) << key;
  for (const char* file : {"out/skin_calibration.json", "out/skin_calibration_curves.csv", "out/skin_calibration.png"})
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  // The calibrated case (the first experiment's) carries the fitted values in the units given, and evaluates.
  EXPECT_THAT(file_text(dir / "calibrated.toml"), HasSubstr("model = { alpha = \"0.0183 N\", tau = \"6.25 /mm\" }"));
  EXPECT_EQ(run_cli(dir, "evaluate calibrated.toml --json").exit_code, 0);
}

TEST(CalibrateCli, IterationsRunOutGiveExit3WithResults) {
  const fs::path dir = analytic_problem("not-converged", 1);
  const auto run = run_cli(dir, "calibrate fit.toml --no-plot --out out");
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_THAT(run.out, HasSubstr("not-converged"));
  EXPECT_THAT(run.err, HasSubstr("iteration 1"));  // progress per iteration
  EXPECT_TRUE(fs::exists(dir / "out/skin_calibration.json"));
}

TEST(CalibrateCli, BadInputExitsWith2AndWritesNothing) {
  const fs::path dir = analytic_problem("bad", 50);
  std::string text = file_text(dir / "fit.toml");
  text.replace(text.find("bounds = [\"0.001 N\", \"0.1 N\"]"), 29, "bounds = [\"0.05 N\", \"0.1 N\"]");
  put(dir / "bad.toml", text);
  const auto run = run_cli(dir, "calibrate bad.toml --out out --write-case c.toml");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("bad.toml:6: key 'parameters[0].initial': lies outside bounds"));
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_FALSE(fs::exists(dir / "c.toml"));
}

}  // namespace
