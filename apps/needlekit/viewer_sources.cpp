#include "viewer_sources.hpp"

#include "resources_root.hpp"

namespace needlekit::cli {

io::ViewerSources viewer_sources() {
  return io::ViewerSources{resources_root({"web/viewer/needlekit_viewer.js"}) / "web" / "viewer"};
}

}  // namespace needlekit::cli
