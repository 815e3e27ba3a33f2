#include "viewer_sources.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "needlekit/core/errors.hpp"

namespace needlekit::cli {

io::ViewerSources viewer_sources() {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  if (const char* root = std::getenv("NEEDLEKIT_ROOT")) candidates.emplace_back(fs::path(root) / "web" / "viewer");
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) candidates.push_back(exe.parent_path().parent_path() / "share" / "needlekit" / "web" / "viewer");
#ifdef NEEDLEKIT_SOURCE_DIR
  candidates.push_back(fs::path(NEEDLEKIT_SOURCE_DIR) / "web" / "viewer");
#endif
  std::string searched;
  for (const fs::path& candidate : candidates) {
    if (fs::exists(candidate / "needlekit_viewer.js")) return io::ViewerSources{candidate};
    searched += " " + candidate.string();
  }
  throw IoError(fmt::format("cannot find needlekit's 3D viewer (web/viewer/needlekit_viewer.js); searched:{} (set "
                            "NEEDLEKIT_ROOT to the needlekit source tree)",
                            searched));
}

}  // namespace needlekit::cli
