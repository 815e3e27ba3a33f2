// Scratch files for tests that write and read files.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace needlekit::test {

// A fresh, empty directory for one test's files.
inline std::filesystem::path scratch_directory(const std::string& name) {
  const auto dir = std::filesystem::path(testing::TempDir()) / ("needlekit_" + name);
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
