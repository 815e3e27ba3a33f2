// The files of a 3D view (docs/views.md): the data file NAME_view.js, which adds one view to the global
// window.needlekitViews (a classic script: Chromium blocks fetch() and modules from file://), the page NAME_view.html
// that shows it, and the viewer folder beside them: needlekit's viewer (web/viewer) and three.js with its orbit
// controls from Debian's libjs-three, copied so that the folder opens from file:// with no network.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "needlekit/core/atomic_file.hpp"

namespace needlekit::io {

// The relative folder of the viewer's files, beside the pages that use them.
inline constexpr const char* kViewerFolder = "viewer";

// The text of NAME_view.js for a view (io/indentation_view.hpp, io/patch_view.hpp).
std::string view_script(const nlohmann::json& view);

// The text of a page showing the views of the data files `scripts` (paths relative to the page), with the viewer
// in `viewer_folder` (relative to the page).
std::string view_page(const std::string& title, const std::vector<std::string>& scripts,
                      const std::string& viewer_folder = kViewerFolder);

struct ViewerSources {
  std::filesystem::path viewer;  // needlekit's web/viewer (needlekit_viewer.js, needlekit_viewer.css)
  std::filesystem::path three = "/usr/share/javascript/three";  // libjs-three: three.min.js, examples/js/controls
};

// The viewer folder's files: (file name, content). Throws IoError naming a file that cannot be read (and, for
// three.js, the Debian package libjs-three that provides it: scripts/install-deps).
std::vector<std::pair<std::string, std::string>> viewer_files(const ViewerSources& sources);

using ViewerFiles = std::vector<std::pair<std::string, std::string>>;

// Stages DIRECTORY/viewer/* (`viewer`: viewer_files, read before a long run so that a missing file fails first) and
// DIRECTORY/PAGE (view_page of `scripts`, relative to DIRECTORY) in `files`, creating the viewer folder; returns the
// page's path. Throws IoError as StagedFiles.
std::filesystem::path stage_view_page(StagedFiles& files, const std::filesystem::path& directory,
                                      const std::string& page, const std::string& title,
                                      const std::vector<std::string>& scripts, const ViewerFiles& viewer);

}  // namespace needlekit::io
