// Where the CLI finds the 3D viewer's files (docs/views.md): needlekit's web/viewer in $NEEDLEKIT_ROOT, the install
// prefix's share/needlekit or the source tree this tool was built from; three.js from Debian's libjs-three.
#pragma once
#include "needlekit/io/view_page.hpp"

namespace needlekit::cli {

// Throws IoError naming the folders searched when web/viewer is in none of them.
io::ViewerSources viewer_sources();

}  // namespace needlekit::cli
