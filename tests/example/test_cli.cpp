// The needlekit tool on the examples: the dissertation's numbers come out of `evaluate` and `optimize`, `sweep`
// writes a CSV with units, and bad input exits with code 2, one error line naming the key, and no output file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/needle/needle_geometry.hpp"

#include "../support/cli_run.hpp"

using needlekit::test::CliRun;
using needlekit::test::kExamples;
using needlekit::test::file_text;
using testing::HasSubstr;

namespace {

// Each test runs the tool in a fresh temporary directory.
class Cli : public needlekit::test::CliTest {
protected:
  Cli() : CliTest("cli") {}

  std::filesystem::path write(const std::string& name, const std::string& content) const {
    std::ofstream(dir_ / name) << content;
    return dir_ / name;
  }
};

void expect_relative(double actual, double expected, double tolerance) {
  EXPECT_NEAR(actual / expected, 1.0, tolerance) << "got " << actual << ", expected " << expected;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_F(Cli, EvaluateSolidConeReproducesSection6_3_1) {
  const CliRun r = run("evaluate " + kExamples + "evaluate_table_6_1_cone.toml --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  expect_relative(json["performance_index_per_um"].get<double>(), 1.288e-4, 1e-3);
  expect_relative(json["deformation_um"].get<double>(), 42.98, 1e-3);
  EXPECT_EQ(json["status"], "ok");
  EXPECT_TRUE(json["small_tip_branch"].get<bool>());
}

TEST_F(Cli, EvaluateCylinderIsTooShort) {
  const CliRun r = run("evaluate " + kExamples + "evaluate_table_6_1_cylinder.toml --json --out result.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["status"], "too_short");
  EXPECT_THAT(json["reason"].get<std::string>(), HasSubstr("target depth"));
  expect_relative(json["deformation_um"].get<double>(), 580.0, 1e-3);
  EXPECT_EQ(json["performance_index_per_um"].get<double>(), 0.0);
  EXPECT_EQ(nlohmann::json::parse(file_text(dir_ / "result.json")), json);  // --out holds the same object
}

TEST_F(Cli, EvaluateTableNamesEveryUnit) {
  const CliRun r = run("evaluate " + kExamples + "evaluate_table_6_1_bevel_hollow.toml");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"deformation d", "um^2", "um^3", "critical buckling load", " N", "1/um", "status",
                           "reason"}) {
    EXPECT_THAT(r.out, HasSubstr(text));
  }
  EXPECT_THAT(r.out, HasSubstr("1.637"));  // the hollow bevel's MPI of §6.3.1, 1.637e-5 /um
}

TEST_F(Cli, BadInputExitsWithCode2AndWritesNothing) {
  write("bare.toml", "[needle]\nshape = \"cone\"\ntip_diameter = 30\nbase_diameter = \"150 um\"\nlength = \"500 um\"\n"
                     "material = \"silicon\"\n[array]\nneedles_per_row = 10\nwidth = \"1 cm\"\n");
  CliRun r = run("evaluate bare.toml --json --out result.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, testing::StartsWith("needlekit: error: bare.toml:3: key 'needle.tip_diameter'"));
  EXPECT_EQ(lines_of(r.err).size(), 1u);
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(std::filesystem::exists(dir_ / "result.json"));

  write("typo.toml", "[needle]\nshape = \"cone\"\ntip_diam = \"30 um\"\n");
  r = run("sweep typo.toml --vary length=300um:500um:50um --csv sweep.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("needlekit: error: typo.toml:3: unknown key 'needle.tip_diam'"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "sweep.csv"));

  r = run("evaluate missing.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("needlekit: error: missing.toml"));

  r = run("sweep " + kExamples + "evaluate_table_6_1_cone.toml --vary length=300:500um:50um --csv sweep.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--vary length (from)"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "sweep.csv"));

  r = run("sweep " + kExamples + "evaluate_table_6_1_cone.toml --vary length=500um:300um:50um");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--vary"));

  r = run("optimize " + kExamples + "optimize_fig_6_20_cone_solid.toml --top 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("needlekit: error:"));

  r = run("evaluate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, testing::StartsWith("needlekit: error:"));
}

TEST_F(Cli, BruteForceRefusesHugeSpaces) {
  // The hollow cone with 1 um steps has 2.1e13 points: brute force refuses, naming the way out.
  std::string space = file_text(kExamples + "optimize_certified_1um_cone_solid.toml");
  space.replace(space.find("hollow = false"), 14, "hollow = true");
  space += "bore_diameter = [\"20 um\", \"50 um\", \"1 um\"]\n";
  write("huge.toml", space);
  const CliRun r = run("optimize huge.toml --out result.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, testing::StartsWith("needlekit: error: huge.toml"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "result.json"));
}

TEST_F(Cli, SweepWritesCsvWithUnits) {
  const CliRun r = run("sweep " + kExamples + "evaluate_table_6_1_cone.toml --vary base_diameter=50um:300um:10um "
                    "--csv sweep.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(file_text(dir_ / "sweep.csv"));
  ASSERT_EQ(lines.size(), 1u + 26u);  // header + 50, 60, ..., 300 um
  EXPECT_EQ(lines[0],
            "base_diameter_um,performance_index_per_um,status,deformation_um,cutting_depth_um,Q_um2,"
            "puncture_force_N,critical_buckling_load_N,buckling_force_N,reason");
  EXPECT_THAT(lines[1], testing::StartsWith("50,"));
  EXPECT_THAT(lines[26], testing::StartsWith("300,"));
  const auto index_of = [](const std::string& row) { return std::stod(row.substr(row.find(',') + 1)); };
  EXPECT_GT(index_of(lines[26]), index_of(lines[1]));  // Fig 6.18: the index grows with the base diameter

  // Without --csv the CSV goes to stdout; a needle count is dimensionless.
  const CliRun counts = run("sweep " + kExamples + "evaluate_table_6_1_cone.toml --vary needles_per_row=5:25:5");
  ASSERT_EQ(counts.exit_code, 0) << counts.err;
  const std::vector<std::string> rows = lines_of(counts.out);
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_THAT(rows[0], testing::StartsWith("needles_per_row,performance_index_per_um,"));
}

TEST_F(Cli, OptimizeSolidCylinderReproducesTable6_3) {
  const CliRun r = run("optimize " + kExamples + "optimize_fig_6_20_cylinder_solid.toml --json --top 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["status"], "optimal");
  const auto& best = json["best"];
  EXPECT_EQ(best["needles_per_row"], 25);
  EXPECT_DOUBLE_EQ(best["tip_diameter_um"].get<double>(), 80.0);
  EXPECT_DOUBLE_EQ(best["base_diameter_um"].get<double>(), 80.0);
  EXPECT_DOUBLE_EQ(best["width_um"].get<double>(), 6000.0);
  EXPECT_DOUBLE_EQ(best["length_um"].get<double>(), 500.0);  // the only feasible L for D = 80 um (d = 445 um)
  expect_relative(best["performance_index_per_um"].get<double>(), 0.001745, 1e-3);
  EXPECT_EQ(json["top"].size(), 3u);
  EXPECT_EQ(json["top"][0]["details"]["status"], "ok");
  EXPECT_EQ(json["grid_points"], 21 * 13 * 6 * 5);
  EXPECT_EQ(json["evaluated"], json["grid_points"]);
  EXPECT_GT(json["feasible"].get<int>(), 0);
}

TEST_F(Cli, HelpShowsUnitsAndRanges) {
  const CliRun main_help = run("--help");
  EXPECT_EQ(main_help.exit_code, 0);
  for (const char* command : {"evaluate", "optimize", "sweep", "materials"}) EXPECT_THAT(main_help.out, HasSubstr(command));
  const CliRun optimize = run("optimize --help");
  EXPECT_EQ(optimize.exit_code, 0);
  EXPECT_THAT(optimize.out, HasSubstr("--top K"));
  EXPECT_THAT(optimize.out, HasSubstr(">= 1"));
  EXPECT_THAT(optimize.out, HasSubstr("[\"30 um\", \"150 um\", \"10 um\"]"));
  const CliRun evaluate = run("evaluate --help");
  EXPECT_THAT(evaluate.out, HasSubstr("[0, 90) deg"));
  const CliRun sweep = run("sweep --help");
  EXPECT_THAT(sweep.out, HasSubstr("PARAM=FROM:TO:STEP"));
}

TEST_F(Cli, MaterialsListsPresetsWithUnitsAndSources) {
  const CliRun r = run("materials");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("silicon"));
  EXPECT_THAT(r.out, HasSubstr("169 GPa"));
  EXPECT_THAT(r.out, HasSubstr("MPa"));
  EXPECT_THAT(r.out, HasSubstr("source: "));
}

TEST_F(Cli, MeshWritesAClosedStlWhoseVolumeMatchesTheNeedle) {
  for (const std::string name : {"evaluate_table_6_1_bevel_hollow.toml", "evaluate_table_6_1_cone.toml"}) {
    const CliRun r = run("mesh " + kExamples + name + " --out needle.stl --unit um --segments 128");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto mesh = needlekit::geometry::read_stl(dir_ / "needle.stl", 1e-6);
    const auto report = needlekit::geometry::topology_report(mesh);
    EXPECT_TRUE(report.closed && report.consistently_oriented) << name;
    const auto design = needlekit::io::read_design_file(kExamples + name);
    EXPECT_NEAR(needlekit::geometry::signed_volume(mesh) / needlekit::needle::volume(design.design.needle), 1.0, 1e-3)
        << name;
  }
  const CliRun bad = run("mesh " + kExamples + "evaluate_table_6_1_cone.toml --out needle2.stl --unit furlong");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--unit"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "needle2.stl"));
}
