// needlekit_fuzz_replay TARGET FILE_OR_DIRECTORY...: runs one fuzz target (fuzz_target.hpp) over every file given
// (directories: every regular file in them, sorted), as the libFuzzer executable would, and reports how many ran.
// Exit 0 when every input was accepted or refused with a message; a crash or an unexpected exception fails the test.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "fuzz_target.hpp"

namespace needlekit::fuzz {
namespace {

std::map<std::string, TargetFunction, std::less<>>& targets() {
  static std::map<std::string, TargetFunction, std::less<>> registry;
  return registry;
}

}  // namespace

bool register_target(std::string_view name, TargetFunction function) {
  targets().emplace(std::string(name), function);
  return true;
}

}  // namespace needlekit::fuzz

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const auto& targets = needlekit::fuzz::targets();
  if (argc < 3 || targets.find(std::string_view(argv[1])) == targets.end()) {
    std::fprintf(stderr, "usage: %s TARGET FILE_OR_DIRECTORY...\ntargets:", argv[0]);
    for (const auto& [name, function] : targets) std::fprintf(stderr, " %s", name.c_str());
    std::fprintf(stderr, "\n");
    return 2;
  }
  const auto target = targets.find(std::string_view(argv[1]))->second;
  std::vector<fs::path> files;
  for (int i = 2; i < argc; ++i) {
    const fs::path path = argv[i];
    if (fs::is_directory(path)) {
      for (const auto& entry : fs::directory_iterator(path))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else if (fs::is_regular_file(path)) {
      files.push_back(path);
    } else {
      std::fprintf(stderr, "%s: no such file or directory\n", path.c_str());
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "no inputs for %s\n", argv[1]);
    return 2;
  }
  for (const fs::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    try {
      target(bytes);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s: unexpected exception: %s\n", argv[1], file.c_str(), e.what());
      return 1;
    }
  }
  std::printf("%s: %zu inputs replayed, none crashed\n", argv[1], files.size());
  return 0;
}
