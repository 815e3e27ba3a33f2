// The same case gives the same mesh, bit for bit, whatever the case file's name, the output folder's path and the
// size of the environment (issue 16: with Gmsh's HXT the count varied by 1.3 % with these alone, since its result
// followed the heap layout). `tissue-mesh` runs twice in different folders; the VTU files must be identical.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/cli_run.hpp"

namespace needlekit {
namespace {

constexpr const char* kCase = R"([tissue]
preset = "skin"
width = "1200 um"
length = "1200 um"
height = "600 um"

[mesh]
size_at_tip = "30 um"
size_far = "200 um"
refinement_radius = "150 um"
)";

TEST(MeshDeterminism, SameMeshWhateverTheFileNamesPathsAndEnvironment) {
  const auto first = test::fresh_directory("determinism-a");
  const auto second = test::fresh_directory("determinism-b-with-a-much-longer-folder-name");
  std::ofstream(first / "c.toml") << kCase;
  std::ofstream(second / "a_much_longer_case_file_name_than_the_other.toml") << kCase;
  const test::CliRun a = test::run_cli(first, "tissue-mesh c.toml --out o --json");
  // A larger environment for the second run (the tool inherits it through std::system).
  ::setenv("NEEDLEKIT_TEST_PADDING", std::string(20000, 'x').c_str(), 1);
  const test::CliRun b = test::run_cli(
      second, "tissue-mesh a_much_longer_case_file_name_than_the_other.toml --out deeper/output/folder --json");
  ::unsetenv("NEEDLEKIT_TEST_PADDING");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string mesh_a = test::file_text(first / "o" / "tissue.vtu");
  const std::string mesh_b = test::file_text(second / "deeper" / "output" / "folder" / "tissue.vtu");
  ASSERT_GT(mesh_a.size(), 10000u);
  EXPECT_TRUE(mesh_a == mesh_b) << "the two meshes differ: " << mesh_a.size() << " and " << mesh_b.size() << " bytes";
  std::filesystem::remove_all(first);
  std::filesystem::remove_all(second);
}

}  // namespace
}  // namespace needlekit
