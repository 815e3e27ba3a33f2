// `needlekit surface`: the report of a body surface (counts, size, a geodesic distance) and the refusal of unusable
// meshes with exit code 2 and one line saying what is wrong.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/analytic_surfaces.hpp"
#include "../support/scratch_files.hpp"

using testing::HasSubstr;

namespace {

// Exit code and combined output of `needlekit ARGUMENTS`.
std::pair<int, std::string> run_cli(const std::string& arguments) {
  FILE* pipe = ::popen((std::string("'") + NEEDLEKIT_CLI + "' " + arguments + " 2>&1").c_str(), "r");
  std::string out;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

std::string cube_obj(bool flip_one) {
  const auto cube = needlekit::test::cube_mesh(2.0);
  std::string text;
  for (const auto& v : cube.vertices) text += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
                                              std::to_string(v.z()) + "\n";
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
    const auto& f = cube.triangles[t];
    const bool flip = flip_one && t == 4;
    text += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[flip ? 2 : 1] + 1) + " " +
            std::to_string(f[flip ? 1 : 2] + 1) + "\n";
  }
  return text;
}

}  // namespace

TEST(SurfaceCli, ReportsACubeAndTheGeodesicBetweenOppositeCorners) {
  const auto dir = needlekit::test::scratch_directory("surface_cli_cube");
  needlekit::test::write_text(dir / "cube.obj", cube_obj(false));
  // In cm (a 2 mm cube would be an implausibly small body surface: a warning on the merged output).
  const auto [code, out] = run_cli("surface '" + (dir / "cube.obj").string() + "' --unit cm --json --geodesic 0 7");
  ASSERT_EQ(code, 0) << out;
  const auto report = nlohmann::json::parse(out);
  EXPECT_EQ(report["vertices"], 8);
  EXPECT_EQ(report["triangles"], 12);
  EXPECT_EQ(report["closed"], true);
  EXPECT_EQ(report["coincident_vertices"], 0);
  EXPECT_NEAR(report["area_mm2"].get<double>(), 2400.0, 1e-7);
  EXPECT_NEAR(report["volume_mm3"].get<double>(), 8000.0, 1e-6);
  EXPECT_NEAR(report["size_mm"][0].get<double>(), 20.0, 1e-11);
  EXPECT_TRUE(report["notes"].empty());
  // Opposite corners of a 2 cm cube: across two faces unfolded into a 2 x 4 rectangle, sqrt(20) cm.
  EXPECT_EQ(report["geodesic"]["status"], "converged");
  EXPECT_NEAR(report["geodesic"]["distance_mm"].get<double>(), 10 * std::sqrt(20.0), 1e-8);
  // Exact to the 12 significant digits the JSON carries (io/json_text.hpp).
  EXPECT_NEAR(report["geodesic"]["euclidean_mm"].get<double>(), 10 * std::sqrt(12.0), 1e-10);
}

TEST(SurfaceCli, WeldsSplitSeams) {
  // The cube with its top face's vertices duplicated (as exporters do along texture seams).
  const auto dir = needlekit::test::scratch_directory("surface_cli_seams");
  std::string obj = cube_obj(false);
  obj += "v 0 0 2\nv 2 0 2\nv 0 2 2\nv 2 2 2\n";
  const auto top = obj.find("f 5 6 7\nf 6 8 7\n");
  ASSERT_NE(top, std::string::npos);
  obj.replace(top, 16, "f 9 10 11\nf 10 12 11\n");
  needlekit::test::write_text(dir / "seams.obj", obj);
  const auto split = run_cli("surface '" + (dir / "seams.obj").string() + "' --unit cm --json");
  ASSERT_EQ(split.first, 0) << split.second;
  EXPECT_EQ(nlohmann::json::parse(split.second)["closed"], false);
  EXPECT_EQ(nlohmann::json::parse(split.second)["coincident_vertices"], 4);
  const auto welded = run_cli("surface '" + (dir / "seams.obj").string() + "' --unit cm --json --weld");
  ASSERT_EQ(welded.first, 0) << welded.second;
  EXPECT_EQ(nlohmann::json::parse(welded.second)["closed"], true);
  EXPECT_EQ(nlohmann::json::parse(welded.second)["vertices"], 8);
}

TEST(SurfaceCli, RefusesUnusableMeshesWithOneLineAndExitCode2) {
  const auto dir = needlekit::test::scratch_directory("surface_cli_bad");
  needlekit::test::write_text(dir / "flipped.obj", cube_obj(true));
  needlekit::test::write_text(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const auto flipped = run_cli("surface '" + (dir / "flipped.obj").string() + "' --unit mm");
  EXPECT_EQ(flipped.first, 2);
  EXPECT_THAT(flipped.second, HasSubstr("flipped.obj: not usable as a body surface: 3 inconsistently oriented"));
  const auto quad = run_cli("surface '" + (dir / "quad.obj").string() + "' --unit mm");
  EXPECT_EQ(quad.first, 2);
  EXPECT_THAT(quad.second, HasSubstr("1 of 1 faces are not triangles"));
  const auto bare = run_cli("surface '" + (dir / "quad.obj").string() + "' --unit 2");
  EXPECT_EQ(bare.first, 2);
  EXPECT_THAT(bare.second, HasSubstr("--unit"));
  const auto vertex = run_cli("surface '" + (dir / "flipped.obj").string() + "' --unit mm --geodesic 0");
  EXPECT_EQ(vertex.first, 2);
  for (const auto& run : {flipped, quad, bare}) {
    EXPECT_EQ(std::count(run.second.begin(), run.second.end(), '\n'), 1) << run.second;
  }
}

TEST(SurfaceCli, ReadsTheSkullInItsArbitraryUnits) {
  const std::filesystem::path file = NEEDLEKIT_SOURCE_DIR "/data/meshes/skull_yahoojapan_10k.obj";
  ASSERT_TRUE(std::filesystem::exists(file)) << "missing repository mesh " << file;
  const auto [code, out] = run_cli("surface '" + file.string() + "' --unit '15.8 mm' --json");
  ASSERT_EQ(code, 0) << out;
  const auto report = nlohmann::json::parse(out);
  EXPECT_EQ(report["triangles"], 10312);
  EXPECT_EQ(report["vertices"], 5154);
  // README: vertex to menton 220 mm, cranial breadth 135 mm at x 15.8.
  EXPECT_NEAR(report["size_mm"][0].get<double>(), 137, 5);
  EXPECT_NEAR(report["size_mm"][1].get<double>(), 220, 5);
}
