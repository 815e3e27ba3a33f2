// Output files are complete or absent: write_file_atomically and StagedFiles (core/atomic_file.hpp) on a normal and
// on a really full file system (a 64 KiB tmpfs), and the interrupt flag (core/interrupt.hpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"

#include "../support/full_filesystem.hpp"
#include "../support/scratch_files.hpp"

namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

std::vector<std::string> names_in(const fs::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicFile, TemporaryNameIsHiddenBesideTheTargetAndKeepsTheExtension) {
  const fs::path temporary = needlekit::temporary_path_for("out/curve.png");
  EXPECT_EQ(temporary.parent_path(), "out");
  EXPECT_EQ(temporary.extension(), ".png");  // matplotlib picks the format from it
  EXPECT_EQ(temporary.filename().string().front(), '.');
  EXPECT_NE(needlekit::temporary_path_for("out/curve.png"), temporary);
}

TEST(StagedFiles, FilesAppearTogetherOnCommitAndNotAtAllWithout) {
  const fs::path dir = needlekit::test::scratch_directory("staged_files");
  {
    needlekit::StagedFiles files;
    files.write(dir / "a.csv", "a");
    files.write(dir / "b.json", "b");
    EXPECT_EQ(names_in(dir).size(), 2u);  // two hidden temporaries
    for (const std::string& name : names_in(dir)) EXPECT_EQ(name.front(), '.') << name;
  }  // an error or an interrupt: destroyed without commit
  EXPECT_TRUE(names_in(dir).empty());

  needlekit::StagedFiles files;
  const fs::path staged = files.write(dir / "a.csv", "a");
  EXPECT_EQ(needlekit::test::read_text(staged), "a");  // readable before the commit (a plot script reads it)
  files.write(dir / "b.json", "b");
  EXPECT_EQ(files.commit(), (std::vector<fs::path>{dir / "a.csv", dir / "b.json"}));
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"a.csv", "b.json"}));
  EXPECT_EQ(needlekit::test::read_text(dir / "b.json"), "b");
}

TEST(StagedFiles, AStagedFileThatWasNotWrittenFailsTheWholeSet) {
  const fs::path dir = needlekit::test::scratch_directory("staged_missing");
  needlekit::StagedFiles files;
  files.write(dir / "curve.csv", "depth_um,force_N\n");
  files.stage(dir / "curve.png");  // the plot script failed and wrote nothing
  try {
    files.commit();
    ADD_FAILURE() << "no error";
  } catch (const needlekit::IoError& error) {
    EXPECT_THAT(error.what(), HasSubstr("curve.png"));
  }
  EXPECT_TRUE(names_in(dir).empty());
}

TEST(OutputDirectory, IsCreatedOrRefusedNamingIt) {
  const fs::path dir = needlekit::test::scratch_directory("output_directory");
  needlekit::create_output_directory(dir / "a" / "b");
  EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
  needlekit::test::write_text(dir / "file", "x");
  try {
    needlekit::create_output_directory(dir / "file");
    ADD_FAILURE() << "no error";
  } catch (const needlekit::IoError& error) {
    EXPECT_THAT(error.what(), HasSubstr((dir / "file").string()));
  }
}

// A full disk: the write that does not fit fails with the system's reason, and no file is left — neither the one
// that did not fit nor, for a staged set, the ones that did.
TEST(AtomicFileDeathTest, AFullFileSystemLeavesNoPartialFile) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path dir = needlekit::test::scratch_directory("full_filesystem");
  EXPECT_EXIT(
      {
        const std::string mounted = needlekit::test::mount_small_tmpfs(dir, 64 * 1024);
        if (!mounted.empty()) {
          std::cerr << "cannot mount a tmpfs: " << mounted;
          std::exit(10);
        }
        int failures = 0;
        try {
          needlekit::write_file_atomically(dir / "big.vtu", std::string(200 * 1024, 'x'));
        } catch (const needlekit::IoError& error) {
          failures += std::string(error.what()).find("No space left on device") != std::string::npos;
        }
        try {
          needlekit::StagedFiles files;
          files.write(dir / "needles.csv", std::string(40 * 1024, 'x'));  // fits
          files.write(dir / "surface.vtu", std::string(40 * 1024, 'x'));  // does not
          files.commit();
        } catch (const needlekit::IoError& error) {
          failures += std::string(error.what()).find("surface.vtu") != std::string::npos;
        }
        const auto left = names_in(dir);
        for (const auto& name : left) std::cerr << "left: " << name << "\n";
        std::cerr << "failures " << failures;
        std::exit(failures == 2 && left.empty() ? 0 : 1);
      },
      testing::ExitedWithCode(0), "failures 2");
}

TEST(Interrupt, FlagIsRequestedCheckedAndCleared) {
  needlekit::clear_interrupt();
  EXPECT_FALSE(needlekit::interrupt_requested());
  EXPECT_NO_THROW(needlekit::throw_if_interrupted());
  needlekit::request_interrupt();
  EXPECT_TRUE(needlekit::interrupt_requested());
  EXPECT_THROW(needlekit::throw_if_interrupted(), needlekit::Interrupted);
  needlekit::clear_interrupt();
  EXPECT_NO_THROW(needlekit::throw_if_interrupted());
}

}  // namespace
