#include "needlekit/core/file_bytes.hpp"

#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <iterator>

#include "needlekit/core/errors.hpp"

namespace needlekit {

std::string read_file_bytes(const std::filesystem::path& path, std::string_view what) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (status.type() == std::filesystem::file_type::not_found) {
    throw IoError(fmt::format("{}: cannot read the {}: no such file", path.string(), what));
  }
  if (std::filesystem::is_directory(status)) {
    throw IoError(fmt::format("{}: cannot read the {}: it is a directory, expected a file", path.string(), what));
  }
  if (!error && !std::filesystem::is_regular_file(status)) {
    throw IoError(fmt::format("{}: cannot read the {}: not a regular file", path.string(), what));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot read the {}: {}", path.string(), what, std::strerror(errno)));
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw IoError(fmt::format("{}: reading the {} failed: {}", path.string(), what, std::strerror(errno)));
  return bytes;
}

}  // namespace needlekit
