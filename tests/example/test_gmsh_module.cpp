// Gmsh lives in a module (libneedlekit_gmsh.so) that the library opens only when it meshes: the dynamic loader's own
// list of the files it opens (LD_DEBUG=files) shows that `materials` and `evaluate` load neither the module nor
// libgmsh (nor OpenCASCADE), and that `tissue-mesh` loads the module of this build and meshes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../support/cli_run.hpp"

using needlekit::test::CliRun;
using needlekit::test::kExamples;
using testing::HasSubstr;
using testing::Not;

namespace {

class GmshModule : public needlekit::test::CliTest {
protected:
  GmshModule() : CliTest("gmsh-module") {}
};

// `needlekit ARGUMENTS` run in `dir` with LD_DEBUG=files: the loader lists every shared object it opens on stderr.
CliRun run_with_loader_log(const std::filesystem::path& dir, const std::string& arguments) {
  const std::string command = "cd '" + dir.string() + "' && LD_DEBUG=files '" + NEEDLEKIT_CLI + "' " + arguments +
                              " > stdout.txt 2> stderr.txt";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, needlekit::test::file_text(dir / "stdout.txt"),
          needlekit::test::file_text(dir / "stderr.txt")};
}

}  // namespace

TEST_F(GmshModule, CommandsThatDoNotMeshLoadNoGmsh) {
  for (const std::string arguments : {std::string("materials"), "evaluate " + kExamples + "evaluate_table_6_1_cone.toml"}) {
    const CliRun r = run_with_loader_log(dir_, arguments);
    ASSERT_EQ(r.exit_code, 0) << arguments << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr("file=libstdc++.so.6"));  // the log is there
    EXPECT_THAT(r.err, Not(HasSubstr("libgmsh"))) << arguments;
    EXPECT_THAT(r.err, Not(HasSubstr("libneedlekit_gmsh"))) << arguments;
    EXPECT_THAT(r.err, Not(HasSubstr("libTKernel"))) << arguments;  // OpenCASCADE
  }
}

TEST_F(GmshModule, MeshingOpensTheModuleOfThisBuild) {
  std::ofstream(dir_ / "block.toml") << R"([tissue]
width = "1000 um"
length = "1000 um"
height = "500 um"

[[tissue.layers]]
name = "silicone"
thickness = "rest"
youngs_modulus = "0.2 MPa"
poisson_ratio = 0.45

[mesh]
size_at_tip = "100 um"
size_far = "250 um"
)";
  const CliRun r = run_with_loader_log(dir_, "tissue-mesh block.toml --json --threads 1 --out out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("libgmsh"));
  // libgmsh is needed by the module of this build tree (the tool's RUNPATH), not by an installed one.
  const std::string build_tree = std::filesystem::path(NEEDLEKIT_CLI).parent_path().parent_path().string();
  bool from_build_tree = false;
  std::istringstream log(r.err);
  for (std::string line; std::getline(log, line);) {
    from_build_tree = from_build_tree || (line.find("file=libgmsh") != std::string::npos &&
                                          line.find("needed by " + build_tree + "/") != std::string::npos &&
                                          line.find("/libneedlekit_gmsh.so") != std::string::npos);
  }
  EXPECT_TRUE(from_build_tree) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  EXPECT_GT(json["elements"].get<int>(), 100);
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out" / "tissue.vtu"));
}
