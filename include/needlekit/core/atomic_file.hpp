// Output files that are either complete or absent. Each file is written to a temporary name in its target's folder
// (".STEM.tmp-PID-N.EXT": hidden, never read as a result) and renamed to its name once every byte is on the file system,
// so that an error, a full disk, Ctrl-C or SIGTERM never leaves a half-written file under the target name. Every
// writer of needlekit (text, JSON, CSV, VTU/PVD, STL, plots drawn by scripts) goes through these functions.
#pragma once
#include <filesystem>
#include <string_view>
#include <vector>

namespace needlekit {

// Creates `directory` (and its parents) for output files and checks that files can be created in it; throws IoError
// naming the directory and the reason (read-only, not a directory, ...) otherwise. Commands call it before any work.
void create_output_directory(const std::filesystem::path& directory);

// A fresh temporary name next to `path` (not created).
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

// Writes `content` to a temporary file next to `path` and renames it to `path`. Throws IoError naming `path` and
// the system's reason (e.g. "No space left on device") on failure, after removing the temporary file.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

// Several output files that appear together or not at all. Each is written to a temporary name when staged;
// commit() renames them all into place (a rename needs no disk space, so a full disk fails while staging, before any
// file appears). A set destroyed without commit() — after an error or an interrupt — removes its temporary files.
class StagedFiles {
public:
  StagedFiles() = default;
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;
  ~StagedFiles();

  // Writes `content` to a temporary file for `path` (IoError as write_file_atomically); returns the temporary
  // file's path, which may be read (e.g. by a plot script) until commit().
  std::filesystem::path write(const std::filesystem::path& path, std::string_view content);
  // A temporary name for `path` that another program fills (e.g. a plot script); commit() renames it (it must exist).
  std::filesystem::path stage(const std::filesystem::path& path);
  // Renames every staged file to its target, in the order staged; returns the targets. Throws IoError (and removes
  // the temporary files not yet renamed) when a staged file is missing — before any rename — or cannot be renamed
  // (rare: the temporary sits in the target's folder; the files renamed before it stay).
  std::vector<std::filesystem::path> commit();

private:
  struct Entry {
    std::filesystem::path temporary;
    std::filesystem::path target;
  };
  std::vector<Entry> entries_;
  void discard() noexcept;
};

}  // namespace needlekit
