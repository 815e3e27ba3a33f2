// `needlekit tissue-mesh` on the shipped skin example (Fig 6.3's four sites) and on bad input: the VTU holds every
// element with its layer's E and nu, the per-layer counts add up, bad input exits 2 naming the key and writes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

using testing::HasSubstr;

namespace {

struct Output {
  int exit_code = -1;
  std::string out;
};

// Runs a shell command with stderr folded into the output.
Output run_shell(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  Output run;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.out.append(buffer, n);
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

Output run_cli(const std::string& arguments) { return run_shell(std::string("'") + NEEDLEKIT_CLI + "' " + arguments); }

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST(TissueMeshCli, SkinExampleWritesLayersToVtu) {
  const auto dir = fresh_dir("needlekit-tissue-mesh");
  const Output run = run_cli(std::string("tissue-mesh '") + NEEDLEKIT_SOURCE_DIR +
                          "/examples/tissue_mesh_skin.toml' --json --threads 2 --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  ASSERT_EQ(json["layers"].size(), 3u);
  int elements = 0;
  for (const auto& layer : json["layers"]) {
    elements += layer["elements"].get<int>();
    // No sliver (quality < 0.08) anywhere (with HXT the minima varied from run to run, 0.10-0.28).
    EXPECT_GT(layer["min_quality"].get<double>(), 0.08) << layer["name"];
  }
  EXPECT_EQ(elements, json["elements"].get<int>());
  EXPECT_DOUBLE_EQ(json["layers"][2]["thickness_um"].get<double>(), 990);
  EXPECT_DOUBLE_EQ(json["layers"][1]["youngs_modulus_MPa"].get<double>(), 0.134);

  // Read the VTU back with meshio: element count, E per layer and the block's volume.
  const auto script = dir / "check.py";
  std::ofstream(script) << "import sys, meshio, numpy as np\n"
                           "m = meshio.read(sys.argv[1]); t = m.cells_dict['tetra']; p = m.points[t]\n"
                           "v = np.einsum('ij,ij->i', np.cross(p[:,1]-p[:,0], p[:,2]-p[:,0]), p[:,3]-p[:,0]) / 6\n"
                           "E = m.cell_data['youngs_modulus_Pa'][0].ravel(); L = m.cell_data['layer'][0].ravel()\n"
                           "print(len(t), v.min() > 0, v.sum(), *[np.unique(E[L == k])[0] for k in range(3)])\n";
  const Output check = run_shell("/usr/bin/python3 '" + script.string() + "' '" + (dir / "out" / "tissue.vtu").string() + "'");
  std::istringstream values(check.out);
  int tets = 0;
  std::string positive;
  double volume = 0, e0 = 0, e1 = 0, e2 = 0;
  values >> tets >> positive >> volume >> e0 >> e1 >> e2;
  EXPECT_EQ(tets, elements) << check.out;
  EXPECT_EQ(positive, "True");
  EXPECT_NEAR(volume, 3000e-6 * 3000e-6 * 1150e-6, 1e-9 * volume);
  EXPECT_DOUBLE_EQ(e0, 100e6);
  EXPECT_DOUBLE_EQ(e1, 0.134e6);
  EXPECT_DOUBLE_EQ(e2, 0.08e6);
  std::filesystem::remove_all(dir);
}

TEST(TissueMeshCli, BadInputExitsTwoAndWritesNothing) {
  const auto dir = fresh_dir("needlekit-tissue-mesh-bad");
  std::ofstream(dir / "bad.toml") << "[[tissue.layers]]\nname = \"sc\"\nthickness = \"0 um\"\nyoungs_modulus = \"1 MPa\"\n";
  const Output run = run_cli("tissue-mesh '" + (dir / "bad.toml").string() + "' --out '" + (dir / "out").string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.out, HasSubstr("bad.toml:3: key 'tissue.layers[0].thickness': '0 um' is not positive"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  std::filesystem::remove_all(dir);
}
