// `needlekit patch` on the shipped examples (dissertation §6.4) with the real neck and skull meshes: the summaries,
// the per-needle CSV, the ParaView files with the meshes' attribution, the Fig 6.25 sweep, and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../support/cli_run.hpp"

using needlekit::test::CliRun;
using needlekit::test::file_text;
using needlekit::test::run_cli;
using testing::HasSubstr;

namespace {

const std::filesystem::path kRepository = NEEDLEKIT_SOURCE_DIR;

class PatchCli : public needlekit::test::CliTest {
protected:
  PatchCli() : CliTest("patch") {}
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::exists(kRepository / "data/meshes/vh_male_head_neck_loop2.obj"))
        << "the repository's body meshes (data/meshes) are missing";
    CliTest::SetUp();
  }
  // Runs `needlekit patch ARGUMENTS` in the scratch folder; returns the exit code, stdout in out_, stderr in err_.
  int run_patch(const std::string& arguments) {
    const CliRun r = CliTest::run("patch " + arguments);
    out_ = r.out;
    err_ = r.err;
    return r.exit_code;
  }
  nlohmann::json summary(const std::string& example, const std::string& out) {
    EXPECT_EQ(run_patch((kRepository / "examples" / example).string() + " --json --out " + out), 0) << err_;
    return nlohmann::json::parse(out_);
  }
  std::string out_, err_;
};

TEST_F(PatchCli, RigidAndFlexiblePatchesOnTheNeck_Section_6_4_1) {
  const nlohmann::json rigid = summary("patch_neck_rigid.toml", "rigid");
  const nlohmann::json flexible = summary("patch_neck_flexible.toml", "flexible");
  EXPECT_EQ(rigid["needles"], 100);
  EXPECT_EQ(flexible["needles"], 100);
  // The rigid patch touches at one node and tilts against the neck: few needles get in, at 15-35 deg.
  EXPECT_LT(rigid["penetrating"].get<int>(), 10);
  EXPECT_GT(rigid["angle_deg"]["min"].get<double>(), 10);
  EXPECT_LT(rigid["angle_deg"]["max"].get<double>(), 40);
  // The flexible one conforms: every needle gets in, within a few degrees of the normal.
  EXPECT_EQ(flexible["penetrating"], 100);
  EXPECT_LT(flexible["angle_deg"]["max"].get<double>(), 5);
  EXPECT_GT(flexible["performance_index_total_per_um"].get<double>(),
            rigid["performance_index_total_per_um"].get<double>());
  // Eqs 5.3/5.4 with F(A) = 0.0712 N: the flexible patch's forces are lower, as in Fig 6.24(b).
  EXPECT_NEAR(flexible["puncture_force_N"].get<double>(), 0.0712057, 1e-6);
  EXPECT_LT(flexible["buckling_force_N"]["max"].get<double>(), rigid["buckling_force_N"]["min"].get<double>());
  EXPECT_LT(flexible["bending_force_N"]["max"].get<double>(), rigid["bending_force_N"]["min"].get<double>());
  const double theta = rigid["angle_deg"]["max"].get<double>() * M_PI / 180;
  EXPECT_NEAR(rigid["buckling_force_N"]["max"].get<double>(), 0.0712057 / std::cos(theta), 1e-6);
  EXPECT_NEAR(rigid["spring_energy_mJ"]["total"].get<double>(), 0, 1e-15);  // a rigid body
  EXPECT_LT(flexible["fit_ms"].get<double>(), 1000);

  // The outputs: one CSV row per needle with units in the header, ParaView files, the mesh attribution.
  const std::string csv = file_text(dir_ / "flexible/needles.csv");
  EXPECT_THAT(csv, HasSubstr("travel_um,penetration_um,angle_deg,buckling_force_N,bending_force_N"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 101);
  for (const char* file : {"surface.vtu", "patch.vtu", "needles.vtu", "summary.json"}) {
    EXPECT_GT(std::filesystem::file_size(dir_ / "flexible" / file), 1000u) << file;
  }
  EXPECT_THAT(file_text(dir_ / "flexible/needles.vtu"), HasSubstr("Name=\"buckling_force_N\""));
  EXPECT_THAT(file_text(dir_ / "flexible/patch.vtu"), HasSubstr("Name=\"strain_energy_mJ\""));
  EXPECT_THAT(file_text(dir_ / "flexible/ATTRIBUTION.md"), HasSubstr("CC BY 4.0"));

  // The static equilibrium of the same patch also conforms (beyond the dissertation).
  const nlohmann::json equilibrium = summary("patch_neck_equilibrium.toml", "equilibrium");
  EXPECT_EQ(equilibrium["status"], "ok");
  EXPECT_EQ(equilibrium["penetrating"], 100);
  EXPECT_LT(equilibrium["angle_deg"]["max"].get<double>(), 10);
}

TEST_F(PatchCli, SpringEnergySweepOnTheNeck_Figure_6_25) {
  ASSERT_EQ(run_patch((kRepository / "examples/patch_neck_20mm.toml").string() +
                " --sweep max_spring_energy=0.005mJ:0.05mJ:4 --out fig"),
            0)
      << err_;
  const std::string csv = file_text(dir_ / "fig/sweep.csv");
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  EXPECT_THAT(line, HasSubstr("max_spring_energy_mJ,performance_index_mean_per_um"));
  std::vector<double> energy, index;
  while (std::getline(lines, line)) {
    energy.push_back(std::stod(line));
    index.push_back(std::stod(line.substr(line.find(',') + 1)));
  }
  ASSERT_EQ(energy.size(), 4u);
  EXPECT_NEAR(energy.front(), 0.005, 1e-12);
  EXPECT_NEAR(energy.back(), 0.05, 1e-12);
  // Fig 6.25: the mean index grows with the allowed spring energy (a more flexible patch conforms better).
  for (std::size_t i = 1; i < index.size(); ++i) EXPECT_GT(index[i], index[i - 1]) << "step " << i;
}

TEST_F(PatchCli, ConicNeedlesOnTheSkullNeitherBuckleNorBend_Section_6_4_3) {
  for (const char* example : {"patch_skull.toml", "patch_skull_20mm.toml"}) {
    const nlohmann::json s = summary(example, "skull");
    EXPECT_EQ(s["needles"], 100) << example;
    EXPECT_EQ(s["penetrating"], 100) << example;  // "all conic microneedles penetrated the soft tissue"
    EXPECT_EQ(s["buckled"], 0) << example;        // "no structural failures were detected"
    EXPECT_EQ(s["bent"], 0) << example;
    // §6.4.3: buckling forces 0.0712-0.0718 N.
    EXPECT_GE(s["buckling_force_N"]["min"].get<double>(), 0.0712);
    EXPECT_LE(s["buckling_force_N"]["max"].get<double>(), 0.0718);
  }
  EXPECT_THAT(file_text(dir_ / "skull/ATTRIBUTION.md"), HasSubstr("YahooJAPAN"));
}

TEST_F(PatchCli, BadInputExitsWithCode2AndNoOutput) {
  const std::string base = file_text(kRepository / "examples/patch_neck_flexible.toml");
  auto write_case = [&](const std::string& from, const std::string& to) {
    std::string text = base;
    text.replace(text.find(from), from.size(), to);
    const std::string mesh = "mesh = \"../data/meshes/";
    text.replace(text.find(mesh), mesh.size(), "mesh = \"" + (kRepository / "data/meshes/").string());
    std::ofstream(dir_ / "case.toml") << text;
  };
  write_case("spring_constant = \"1 N/mm\"", "spring_constant = \"-1 N/mm\"");
  EXPECT_EQ(run_patch("case.toml --out bad"), 2);
  EXPECT_THAT(err_, HasSubstr("patch.spring_constant"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad"));

  write_case("center_vertex = 2243", "center = [\"0 mm\", \"0 mm\", \"0 mm\"]");
  EXPECT_EQ(run_patch("case.toml --out bad"), 2);
  EXPECT_THAT(err_, HasSubstr("from the surface"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad"));

  // A non-manifold surface: three triangles on one edge.
  std::ofstream(dir_ / "fan.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
  std::string text = base;
  const std::string mesh = "../data/meshes/vh_male_head_neck_loop2.obj";
  text.replace(text.find(mesh), mesh.size(), "fan.obj");
  std::ofstream(dir_ / "case.toml") << text;
  EXPECT_EQ(run_patch("case.toml --out bad"), 2);
  EXPECT_THAT(err_, HasSubstr("fan.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad"));

  EXPECT_EQ(run_patch((kRepository / "examples/patch_neck_rigid.toml").string() + " --sweep max_spring_energy=1mJ:2mJ:3"), 2);
  EXPECT_THAT(err_, HasSubstr("needs a flexible patch"));
}

}  // namespace
