// Scratch files for tests that write and read files.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace needlekit::test {

// A fresh, empty directory for one test's files. CTest runs every test of a fixture in its own process at the same
// time, so the directory is named after the running test as well as `name`: two tests never share one.
inline std::filesystem::path scratch_directory(const std::string& name) {
  const testing::TestInfo* running = testing::UnitTest::GetInstance()->current_test_info();
  std::string test_name = running ? std::string(running->test_suite_name()) + "." + running->name() : "no_test";
  for (char& c : test_name)
    if (c == '/') c = '_';  // parameterised tests are named Prefix/Suite.Name/N
  const auto dir = std::filesystem::path(testing::TempDir()) / ("needlekit_" + name + "_" + test_name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace needlekit::test
