// `needlekit insert`: the complete insertion curve from a given pre-puncture curve (fast, no FE) and from the FE
// (the §6.2 examples in a quick mode), its CSV/JSON/PNG outputs, the fit of S, and bad input (exit 2, one line, no
// output files).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "../support/cli_run.hpp"

using needlekit::test::CliRun;
using needlekit::test::file_text;
using needlekit::test::run_cli;
using testing::HasSubstr;
using namespace needlekit;

namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) { return needlekit::test::fresh_directory("insert-" + name); }

void put(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// The sharp bevel of §6.2 on a given pre-puncture curve; `extra` goes into [post_puncture].
std::string sharp_bevel_case(const std::string& extra = "") {
  return "name = \"sb\"\n[needle]\nshape = \"bevel\"\ntip_diameter = \"10 um\"\nbase_diameter = \"230 um\"\n"
         "length = \"1000 um\"\n[tissue]\npreset = \"silicone-0.2mpa\"\n[loading]\ndepth = \"300 um\"\n"
         "[puncture]\ncritical_pressure = \"0.663 MPa\"\n"
         "[post_puncture]\nstiffness = \"0.2 N/mm2\"\nscale = 0.168\nfinal_depth = \"1000 um\"\nsamples = 50\n" +
         extra + "[pre_puncture]\ncurve = \"pre.csv\"\n";
}

// Pre-puncture curve of the experiment's sharp bevel: quadratic to 0.23 mm and 0.014 N.
std::string experiment_pre_curve() {
  std::string csv = "depth_mm,force_N\n";
  for (int k = 1; k <= 10; ++k) {
    const double x = 0.023 * k;
    csv += std::to_string(x) + "," + std::to_string(0.014 * (x / 0.23) * (x / 0.23)) + "\n";
  }
  return csv;
}

insertion::PostPunctureLoads sharp_bevel_loads() {
  const auto mesh = needle::needle_surface_mesh({needle::Shape::Bevel, 10e-6, 230e-6, 0, 1000e-6}, {64, 16});
  return insertion::post_puncture_loads(mesh);
}

TEST(InsertCli, GivenPrePunctureCurveGivesTheCompleteCurveWithPlot) {
  const fs::path dir = fresh_dir("pre");
  put(dir / "pre.csv", experiment_pre_curve());
  put(dir / "case.toml", sharp_bevel_case());
  const CliRun r = run_cli(dir, "insert case.toml --json --out results");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_NEAR(json["puncture_depth_um"].get<double>(), 230, 1e-6);
  EXPECT_NEAR(json["puncture_force_N"].get<double>(), 0.014, 1e-9);
  // The inputs echoed from the parameter tables (io/parameter_json.hpp): the case's and the defaults.
  const auto& inputs = json["inputs"];
  EXPECT_NEAR(inputs["loading"]["depth_m"].get<double>(), 300e-6, 1e-18);
  EXPECT_NEAR(inputs["puncture"]["critical_pressure_Pa"].get<double>(), 0.663e6, 1e-6);
  EXPECT_EQ(inputs["post_puncture"]["cap_at_cutting_pressure"],
            insertion::PostPunctureOptions{}.cap_at_cutting_pressure);
  EXPECT_EQ(inputs["post_puncture"]["reference_radius_m"], 0.0);
  EXPECT_NEAR(inputs["post_puncture"]["stiffness_Pa"].get<double>(), 0.2e6, 1e-6);
  EXPECT_EQ(inputs["post_puncture"]["scale"], 0.168);
  EXPECT_EQ(inputs["post_puncture"]["samples"], 50);
  EXPECT_EQ(inputs["post_puncture"]["occlusion_test"], false);
  const auto& phase = json["phase"];
  const auto& depth = json["depth_um"];
  const auto& force = json["force_N"];
  ASSERT_EQ(phase.size(), depth.size());
  ASSERT_EQ(force.size(), depth.size());
  EXPECT_EQ(phase.front(), "indentation");
  EXPECT_EQ(phase.back(), "cutting");
  EXPECT_NEAR(depth.back().get<double>(), 1000, 1e-9);
  // The cutting force is the library's post-puncture force of the same needle mesh.
  const auto loads = sharp_bevel_loads();
  EXPECT_NEAR(force.back().get<double>(), insertion::post_puncture_force(loads, 1e-3, 0.2e6, 0.168), 1e-12);
  EXPECT_GT(json["relaxation_drop_N"].get<double>(), 0.0);  // the cutting force at 0.23 mm is below 0.014 N
  EXPECT_EQ(json["classification"]["alpha"].get<int>() > 0, true);
  // Files: CSV with units and markers, JSON, and a PNG.
  const std::string csv = file_text(dir / "results/sb_insertion.csv");
  EXPECT_THAT(csv, testing::StartsWith("depth_um,force_N,phase,punctured_needles,marker\n"));
  EXPECT_THAT(csv, HasSubstr(",indentation,0,puncture\n"));
  EXPECT_THAT(csv, HasSubstr(",cutting,1,relaxed\n"));
  EXPECT_EQ(nlohmann::json::parse(file_text(dir / "results/sb_insertion.json"))["force_N"], force);
  const std::string png = file_text(dir / "results/sb_insertion.png");
  ASSERT_GT(png.size(), 10000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  fs::remove_all(dir);
}

TEST(InsertCli, FitsTheScaleToAMeasuredCurve) {
  const fs::path dir = fresh_dir("fit");
  const auto loads = sharp_bevel_loads();
  std::string measured = "depth_um,force_N\n";
  for (int k = 1; k <= 16; ++k) {
    const double h = 50e-6 * k;
    measured += std::to_string(h * 1e6) + "," + std::to_string(insertion::post_puncture_force(loads, h, 0.2e6, 0.3)) +
                "\n";
  }
  put(dir / "measured.csv", measured);
  put(dir / "pre.csv", experiment_pre_curve());
  put(dir / "case.toml", sharp_bevel_case("measured = \"measured.csv\"\n"));
  const CliRun r = run_cli(dir, "insert case.toml --json --no-plot");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  const double fitted = json["fit"]["scale"].get<double>();
  EXPECT_NEAR(fitted, 0.3, 1e-4);  // to the CSV's printed digits
  EXPECT_LT(json["fit"]["relative_rms"].get<double>(), 1e-4);
  EXPECT_FALSE(fs::exists(dir / "sb_insertion.png"));
  // The curve, the JSON file and the summary use the fitted S, and say that it was fitted and what the case gave.
  EXPECT_EQ(json["scale"].get<double>(), fitted);
  EXPECT_EQ(json["scale_source"], "fitted");
  EXPECT_EQ(json["case_scale"].get<double>(), 0.168);
  EXPECT_NEAR(json["force_N"].back().get<double>(), insertion::post_puncture_force(loads, 1e-3, 0.2e6, fitted), 1e-12);
  EXPECT_EQ(nlohmann::json::parse(file_text(dir / "sb_insertion.json"))["force_N"], json["force_N"]);
  const CliRun text = run_cli(dir, "insert case.toml --no-plot");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("the curve uses the fitted S (the case's S = 0.168)"));
  fs::remove_all(dir);
}

TEST(InsertCli, BadInputExitsWith2AndWritesNothing) {
  const fs::path dir = fresh_dir("bad");
  put(dir / "pre.csv", experiment_pre_curve());
  auto expect_bad = [&](const std::string& case_text, const std::string& fragment) {
    put(dir / "case.toml", case_text);
    const CliRun r = run_cli(dir, "insert case.toml --out results");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr(fragment));
    EXPECT_THAT(r.err, testing::StartsWith("needlekit: error: "));
    EXPECT_FALSE(fs::exists(dir / "results/sb_insertion.csv"));
  };
  std::string no_post = sharp_bevel_case();
  no_post = no_post.substr(0, no_post.find("[post_puncture]")) + "[pre_puncture]\ncurve = \"pre.csv\"\n";
  expect_bad(no_post, "missing table [post_puncture]");
  put(dir / "bad.csv", "depth_um,force_N\n10,0.001\n30,0.002\n20,0.003\n");
  expect_bad(sharp_bevel_case("measured = \"bad.csv\"\n"), "bad.csv:4: depth is not monotonic");
  put(dir / "cols.csv", "depth_um,load_N\n10,0.001\n");
  expect_bad(sharp_bevel_case("measured = \"cols.csv\"\n"), "missing column force_<unit>");

  // Needle meshes: open, inverted.
  auto mesh = needle::needle_surface_mesh({needle::Shape::Cone, 40e-6, 230e-6, 0, 1000e-6}, {32, 4});
  auto open = mesh;
  open.triangles.pop_back();
  geometry::write_stl(open, dir / "open.stl", 1e6);
  auto inverted = mesh;
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  geometry::write_stl(inverted, dir / "inverted.stl", 1e6);
  auto mesh_case = [&](const std::string& file) {
    std::string text = sharp_bevel_case();
    const std::size_t a = text.find("[needle]"), b = text.find("[tissue]");
    return text.substr(0, a) + "[needle]\nmesh = \"" + file + "\"\nmesh_unit = \"um\"\n" + text.substr(b);
  };
  expect_bad(mesh_case("open.stl"), "open");
  expect_bad(mesh_case("inverted.stl"), "inverted");
  fs::remove_all(dir);
}

TEST(InsertCli, NewtonFailureExitsThreeAfterWritingTheConvergedPart) {
  // The sharp bevel on a deterministic graded block (tests/data/insertion), 25 um steps, at most N Newton iterations
  // and no cut-back: with N = 4 the first step converges and the second does not; with N = 3 none does (with the
  // per-element volumetric term; the nodal-averaged default converges one step further here).
  const fs::path dir = fresh_dir("newton");
  auto case_with = [](int iterations) {
    return "name = \"sb\"\n[needle]\nshape = \"bevel\"\ntip_diameter = \"10 um\"\nbase_diameter = \"230 um\"\n"
           "length = \"1000 um\"\n[tissue]\npreset = \"silicone-0.2mpa\"\n[mesh]\nfile = \"" NEEDLEKIT_TEST_DATA_DIR
           "/insertion/graded_block.msh\"\nunit = \"um\"\n[loading]\ndepth = \"300 um\"\nsteps = 12\n"
           "[model]\nlaw = \"neo-hookean\"\ncontact = \"tip-nodes\"\n[puncture]\ncritical_pressure = \"0.663 MPa\"\n"
           "[solver]\nvolumetric = \"element\"\nmax_iterations = " + std::to_string(iterations) + "\nmax_cutbacks = 0\n"
           "[post_puncture]\nstiffness = \"0.2 N/mm2\"\nscale = 0.168\nfinal_depth = \"1000 um\"\n";
  };
  put(dir / "case.toml", case_with(4));
  const CliRun r = run_cli(dir, "insert case.toml --no-plot --out results");
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("solver-failed: the FE indentation stopped: load step 2 of 12"));
  EXPECT_THAT(r.out, HasSubstr("wrote results/sb_insertion.csv, results/sb_insertion.json\n"));
  const auto json = nlohmann::json::parse(file_text(dir / "results/sb_insertion.json"));
  EXPECT_EQ(json["status"], "solver-failed");
  EXPECT_EQ(json["fe"]["status"], "solver-failed");
  EXPECT_EQ(json["depth_um"].size(), 2u);  // 0 and the converged 25 um
  EXPECT_NEAR(json["depth_um"].back().get<double>(), 25, 1e-9);
  EXPECT_THAT(file_text(dir / "results/sb_insertion.csv"), HasSubstr("\n25,"));

  put(dir / "case.toml", case_with(3));
  fs::remove_all(dir / "results");
  const CliRun none = run_cli(dir, "insert case.toml --out results");
  EXPECT_EQ(none.exit_code, 3) << none.out << none.err;
  EXPECT_THAT(none.out, HasSubstr("converged no load step"));
  EXPECT_THAT(none.out, HasSubstr("wrote results/sb_insertion.json\n"));  // only what was written is named
  EXPECT_FALSE(fs::exists(dir / "results/sb_insertion.csv"));
  EXPECT_FALSE(fs::exists(dir / "results/sb_insertion.png"));
  EXPECT_EQ(nlohmann::json::parse(file_text(dir / "results/sb_insertion.json"))["status"], "solver-failed");
  fs::remove_all(dir);
}

TEST(InsertCli, SharpBevelExampleRunsTheFeThenCuts) {
  // examples/insert_sharp_bevel.toml in a quick mode (coarse mesh, 6 load steps): the FE punctures within the first
  // 150 um (the dissertation's simulation: < 20 um; needlekit: 101 um on this 40 um mesh, 48 um on a 20 um mesh),
  // then the cutting phase.
  const fs::path dir = fresh_dir("fe");
  const CliRun r = run_cli(dir, "insert '" NEEDLEKIT_SOURCE_DIR "/examples/insert_sharp_bevel.toml' --json --no-plot "
                                "--size-at-tip '40 um' --size-far '600 um' --steps 6");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["pre_puncture_source"], "fe");
  EXPECT_EQ(json["fe"]["status"], "punctured");
  ASSERT_FALSE(json["puncture_depth_um"].is_null());
  EXPECT_GT(json["puncture_depth_um"].get<double>(), 0.0);
  EXPECT_LT(json["puncture_depth_um"].get<double>(), 150.0);
  EXPECT_GT(json["puncture_force_N"].get<double>(), 0.0);
  EXPECT_EQ(json["phase"].back(), "cutting");
  const auto loads = sharp_bevel_loads();
  EXPECT_NEAR(json["force_N"].back().get<double>(), insertion::post_puncture_force(loads, 1e-3, 0.2e6, 0.168), 1e-12);
  fs::remove_all(dir);
}

}  // namespace
