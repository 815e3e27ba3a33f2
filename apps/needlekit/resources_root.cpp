#include "resources_root.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "needlekit/core/errors.hpp"

namespace needlekit::cli {

std::filesystem::path resources_root(std::initializer_list<std::string_view> files) {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  if (const char* root = std::getenv("NEEDLEKIT_ROOT")) candidates.emplace_back(root);
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) candidates.push_back(exe.parent_path().parent_path() / "share" / "needlekit");
#ifdef NEEDLEKIT_SOURCE_DIR
  candidates.emplace_back(NEEDLEKIT_SOURCE_DIR);
#endif
  for (const fs::path& candidate : candidates) {
    bool complete = true;
    for (std::string_view file : files) complete = complete && fs::exists(candidate / file);
    if (complete) return candidate;
  }
  std::string searched;
  for (const fs::path& candidate : candidates) {
    searched += ' ';
    searched += candidate.string();
  }
  throw IoError(fmt::format("cannot find needlekit's data ({}); searched:{} (set NEEDLEKIT_ROOT to the needlekit "
                            "source tree)",
                            fmt::join(files, ", "), searched));
}

}  // namespace needlekit::cli
