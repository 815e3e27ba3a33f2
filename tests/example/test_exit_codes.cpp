// The tool's exit codes (docs/cli.md "Exit codes", core/exit_codes.hpp), one test each, and what a stopped run leaves
// behind: 0 success; 2 bad input, including an output directory that cannot be written and a really full disk (a
// 64 KiB tmpfs), with no partial file; 3 a numerical failure with the completed steps kept and marked; 130 after
// SIGINT or SIGTERM, with every file it kept complete and marked incomplete.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/cli_signal.hpp"
#include "../support/full_filesystem.hpp"

using needlekit::test::CliRun;
using needlekit::test::file_text;
using needlekit::test::kExamples;
using testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

class ExitCodes : public needlekit::test::CliTest {
protected:
  ExitCodes() : CliTest("exit-codes") {}

  // Runs the tool with a `size` tmpfs (read-only if asked) mounted at DIR/mount; returns its exit code, output and
  // the names left in DIR/mount/out.
  CliRun run_on_small_tmpfs(const std::string& arguments, const std::string& size, bool read_only,
                            std::vector<std::string>& left) const {
    fs::create_directories(dir_ / "mount");
    const std::string command = needlekit::test::with_small_tmpfs(
        dir_ / "mount", size,
        "'" + std::string(NEEDLEKIT_CLI) + "' " + arguments +
            " > stdout.txt 2> stderr.txt; echo \\$? > exit_code.txt; ls -A mount/out > left.txt 2>/dev/null; true",
        read_only);
    EXPECT_EQ(std::system(("cd '" + dir_.string() + "' && " + command).c_str()), 0) << command;
    std::ifstream listing(dir_ / "left.txt");
    for (std::string name; std::getline(listing, name);) left.push_back(name);
    const std::string code = file_text(dir_ / "exit_code.txt");
    return {code.empty() ? -1 : std::stoi(code), file_text(dir_ / "stdout.txt"), file_text(dir_ / "stderr.txt")};
  }
};

// The flat punch on a coarse mesh: a few seconds per run.
const std::string kQuickPunch = "indent " + kExamples + "indent_flat_punch.toml --size-at-tip '60 um' --size-far "
                                                        "'800 um' --depth '10 um'";

// Names of hidden temporaries (".NAME.tmp-...") among `names`.
std::vector<std::string> temporaries(const std::vector<std::string>& names) {
  std::vector<std::string> hidden;
  for (const std::string& name : names)
    if (name.find(".tmp-") != std::string::npos) hidden.push_back(name);
  return hidden;
}

std::vector<std::string> names_in(const fs::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory)) names.push_back(entry.path().filename().string());
  return names;
}

TEST_F(ExitCodes, SuccessIs0AndWritesTheResult) {
  const CliRun r = run("evaluate " + kExamples + "evaluate_table_6_1_cone.toml --out result.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(file_text(dir_ / "result.json"))["status"], "ok");
  EXPECT_TRUE(temporaries(names_in(dir_)).empty());
}

TEST_F(ExitCodes, BadInputIs2AndWritesNothing) {
  std::ofstream(dir_ / "design.toml") << "[needle]\nshape = \"cone\"\ntip_diameter = 30\n";
  const CliRun r = run("evaluate design.toml --out result.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("design.toml:3"));
  EXPECT_FALSE(fs::exists(dir_ / "result.json"));
}

// A read-only output directory is bad input naming the directory, found before the FE run starts.
TEST_F(ExitCodes, ReadOnlyOutputDirectoryIs2NamingIt) {
  std::vector<std::string> left;
  const CliRun r = run_on_small_tmpfs("insert " + kExamples + "insert_cylinder.toml --no-plot --out mount/out", "64k",
                                      true, left);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("mount/out: cannot create the output directory: Read-only file system"));
  EXPECT_THAT(r.err, testing::Not(HasSubstr("internal error")));
  EXPECT_THAT(r.err, testing::Not(HasSubstr("indentation")));  // refused before the FE progress bar
}

// A full disk: `patch --out` writes five files together; the 64 KiB tmpfs takes the first ones but not the
// surface's VTU: exit 2 with the system's reason, and no file at all is left (the set is all-or-nothing).
TEST_F(ExitCodes, FullDiskIs2AndLeavesNoPartialFile) {
  std::vector<std::string> left;
  const CliRun r =
      run_on_small_tmpfs("patch " + kExamples + "patch_neck_rigid.toml --out mount/out", "64k", false, left);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("No space left on device"));
  EXPECT_TRUE(left.empty()) << testing::PrintToString(left);
}

// `indent` writes each step as it completes; on a full disk the files it kept are complete (no temporary left) and
// the run ends with 2.
TEST_F(ExitCodes, FullDiskDuringIndentationKeepsOnlyCompleteFiles) {
  std::vector<std::string> left;
  const CliRun r = run_on_small_tmpfs(kQuickPunch + " --steps 2 --out mount/out", "64k", false, left);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("No space left on device"));
  EXPECT_TRUE(temporaries(left).empty()) << testing::PrintToString(left);
}

// A load step that does not converge (one Newton iteration allowed, no cut-back): exit 3, the result says why, no
// ParaView series is announced that was not written.
TEST_F(ExitCodes, NumericalFailureIs3WithTheResultKept) {
  std::ofstream(dir_ / "case.toml") << file_text(kExamples + "indent_flat_punch.toml")
                                    << "\n[solver]\nmax_iterations = 1\nmax_cutbacks = 0\nresidual_tolerance = 1e-14\n";
  const std::string quick = " --size-at-tip '60 um' --size-far '800 um' --depth '10 um' --steps 1";
  const CliRun r = run("indent case.toml --out results" + quick);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_THAT(r.out, HasSubstr("status: solver-failed"));
  EXPECT_THAT(r.out, testing::Not(HasSubstr(".pvd")));
  const nlohmann::json result = nlohmann::json::parse(file_text(dir_ / "results/flat_punch_result.json"));
  EXPECT_EQ(result["status"], "solver-failed");
  EXPECT_THAT(result["reason"].get<std::string>(), HasSubstr("did not converge"));
  const CliRun json = run("indent case.toml --json" + quick);
  EXPECT_EQ(json.exit_code, 3) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["status"], "solver-failed");
}

// Ctrl-C after the first load step: exit 130, the steps written so far are complete files and the result that
// goes with them says "incomplete".
TEST_F(ExitCodes, InterruptIs130AndMarksWhatWasKeptIncomplete) {
  const fs::path first_step = dir_ / "results/flat_punch_step_001.vtu";
  std::vector<std::string> arguments{"indent", kExamples + "indent_flat_punch.toml", "--size-at-tip", "60 um",
                                     "--size-far", "800 um", "--depth", "100 um", "--steps", "200", "--out",
                                     "results"};
  const CliRun r = needlekit::test::run_cli_and_signal(dir_, arguments, [&] { return fs::exists(first_step); }, SIGINT);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_THAT(r.err, HasSubstr("interrupted"));
  const std::vector<std::string> left = names_in(dir_ / "results");
  EXPECT_TRUE(temporaries(left).empty()) << testing::PrintToString(left);
  const nlohmann::json result = nlohmann::json::parse(file_text(dir_ / "results/flat_punch_result.json"));
  EXPECT_EQ(result["status"], "incomplete");
  const std::size_t steps = result["force_N"].size();
  EXPECT_GE(steps, 1u);
  EXPECT_LT(steps, 200u);
  for (const std::string& name : left) {
    if (fs::path(name).extension() == ".vtu" || fs::path(name).extension() == ".pvd") {
      EXPECT_THAT(file_text(dir_ / "results" / name), testing::EndsWith("</VTKFile>\n")) << name;
    }
  }
}

// SIGTERM during a patch sweep (400 fits, a minute), once the case is read and placed (its output folder exists):
// exit 130 and no sweep files.
TEST_F(ExitCodes, TerminateIs130AndWritesNothingUnfinished) {
  const CliRun r = needlekit::test::run_cli_and_signal(
      dir_,
      {"patch", kExamples + "patch_neck_flexible.toml", "--sweep", "max_spring_energy=0.005mJ:0.05mJ:400", "--out",
       "sweep"},
      [&] { return fs::exists(dir_ / "sweep"); }, SIGTERM);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "sweep/sweep.csv"));
  EXPECT_TRUE(!fs::exists(dir_ / "sweep") || names_in(dir_ / "sweep").empty());
}

}  // namespace
