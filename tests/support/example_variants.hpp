// Variants of an example input file for CLI tests: the example with some text replaced, written next to the test,
// and the checks of a bad-input run (exit 2, one line on stderr naming FILE:LINE and the key, nothing written).
#pragma once
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"

namespace needlekit::test {

using Replacements = std::vector<std::pair<std::string, std::string>>;

// examples/`example` with each `from` replaced by its `to` (the first occurrence; a missing one fails the test),
// written to directory/`name`; returns `name`.
inline std::string write_example_variant(const std::string& example, const Replacements& replacements,
                                         const std::filesystem::path& directory, const std::string& name = "uq.toml") {
  std::string text = file_text(kExamples + example);
  for (const auto& [from, to] : replacements) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  std::ofstream(directory / name) << text;
  return name;
}

// A run of bad input with --out result: exit code 2, one line naming `fragment` and `file`:LINE, no stdout, no
// output folder.
inline void expect_bad_input(const CliRun& r, const std::string& fragment, const std::filesystem::path& directory,
                             const std::string& file = "uq.toml") {
  EXPECT_EQ(r.exit_code, 2) << fragment;
  EXPECT_THAT(r.err, testing::HasSubstr(fragment)) << r.err;
  EXPECT_THAT(r.err, testing::HasSubstr(file + ":")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(std::filesystem::exists(directory / "result"));
}

}  // namespace needlekit::test
