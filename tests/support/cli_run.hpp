// Running the needlekit command-line tool from the example tests: in a given working directory, capturing its exit
// code, standard output and standard error (NEEDLEKIT_CLI is the tool's path, set by tests/CMakeLists.txt).
#pragma once
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace needlekit::test {

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

}  // namespace needlekit::test
