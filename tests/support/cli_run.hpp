// Running the needlekit command-line tool from the example tests: in a given working directory, capturing its exit
// code, standard output and standard error (NEEDLEKIT_CLI is the tool's path, set by tests/CMakeLists.txt).
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

namespace needlekit::test {

// The repository's examples/ folder, with a trailing slash.
inline const std::string kExamples = std::string(NEEDLEKIT_SOURCE_DIR) + "/examples/";

struct CliRun {
  int exit_code = -1;  // -1 when the tool did not exit normally
  std::string out;     // standard output
  std::string err;     // standard error
};

// A whole file's bytes ("" when it cannot be read).
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Runs `needlekit ARGUMENTS` with `directory` as the working directory; stdout.txt and stderr.txt are left there.
inline CliRun run_cli(const std::filesystem::path& directory, const std::string& arguments) {
  const std::string command = "cd '" + directory.string() + "' && '" + NEEDLEKIT_CLI + "' " + arguments +
                              " > stdout.txt 2> stderr.txt";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, file_text(directory / "stdout.txt"),
          file_text(directory / "stderr.txt")};
}

// A fresh, empty directory needlekit-NAME-PID in the system's temporary folder (the process id keeps parallel
// ctest runs apart).
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory =
      std::filesystem::temp_directory_path() / ("needlekit-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

// A fixture whose tests each run the tool in their own fresh directory `dir_`, removed afterwards.
class CliTest : public testing::Test {
protected:
  explicit CliTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = fresh_directory(prefix_ + "-" + testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  CliRun run(const std::string& arguments) const { return run_cli(dir_, arguments); }

  std::filesystem::path dir_;

private:
  std::string prefix_;
};

}  // namespace needlekit::test
