#include "needlekit/core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <string>

#include "needlekit/core/errors.hpp"

namespace needlekit {
namespace {

std::atomic<unsigned> g_counter{0};

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& reason) {
  throw IoError(fmt::format("{}: cannot write: {}", path.string(), reason));
}

// Creates `temporary` and writes `content` to it; on failure removes it and throws IoError naming `target`.
void write_new_file(const std::filesystem::path& temporary, const std::filesystem::path& target,
                    std::string_view content) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) fail(target, std::strerror(errno));
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = n < 0 ? std::strerror(errno) : "the file system accepted no more bytes";
      ::close(fd);
      ::unlink(temporary.c_str());
      fail(target, reason);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) {  // network and some local file systems report a full disk only here
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    fail(target, reason);
  }
}

void rename_into_place(const std::filesystem::path& temporary, const std::filesystem::path& target) {
  if (::rename(temporary.c_str(), target.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    fail(target, reason);
  }
}

}  // namespace

void create_output_directory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  const char* problem = nullptr;
  if (error) {
    throw IoError(fmt::format("{}: cannot create the output directory: {}", directory.string(), error.message()));
  }
  if (!std::filesystem::is_directory(directory, error)) problem = "it exists and is not a directory";
  else if (::access(directory.c_str(), W_OK | X_OK) != 0) problem = std::strerror(errno);
  if (problem != nullptr) {
    throw IoError(fmt::format("{}: cannot write to the output directory: {}", directory.string(), problem));
  }
}

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  // The extension is kept last, for programs that choose the format from the name (matplotlib's savefig).
  return path.parent_path() /
         fmt::format(".{}.tmp-{}-{}{}", path.stem().string(), ::getpid(), g_counter++, path.extension().string());
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path temporary = temporary_path_for(path);
  write_new_file(temporary, path, content);
  rename_into_place(temporary, path);
}

StagedFiles::~StagedFiles() { discard(); }

std::filesystem::path StagedFiles::write(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path temporary = temporary_path_for(path);
  write_new_file(temporary, path, content);
  entries_.push_back({temporary, path});
  return temporary;
}

std::filesystem::path StagedFiles::stage(const std::filesystem::path& path) {
  entries_.push_back({temporary_path_for(path), path});
  return entries_.back().temporary;
}

std::vector<std::filesystem::path> StagedFiles::commit() {
  std::vector<std::filesystem::path> targets;
  for (const Entry& entry : entries_) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(entry.temporary, error)) {
      const std::filesystem::path target = entry.target;
      discard();
      fail(target, "it was not written");
    }
  }
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    try {
      rename_into_place(entries_[i].temporary, entries_[i].target);
    } catch (...) {
      entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      discard();
      throw;
    }
    targets.push_back(entries_[i].target);
  }
  entries_.clear();
  return targets;
}

void StagedFiles::discard() noexcept {
  for (const Entry& entry : entries_) ::unlink(entry.temporary.c_str());
  entries_.clear();
}

}  // namespace needlekit
