#include "needlekit/io/view_page.hpp"

#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/file_bytes.hpp"
#include "needlekit/io/vtu_writer.hpp"

namespace needlekit::io {

std::string view_script(const nlohmann::json& view) {
  return "(window.needlekitViews = window.needlekitViews || []).push(" + view.dump() + ");\n";
}

std::string view_page(const std::string& title, const std::vector<std::string>& scripts,
                      const std::string& viewer_folder) {
  std::string data;
  for (const std::string& script : scripts) data += fmt::format("<script src=\"{}\"></script>\n", xml_escaped(script));
  const std::string folder = xml_escaped(viewer_folder);
  return fmt::format(R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{0}</title>
<link rel="stylesheet" href="{1}/needlekit_viewer.css"></head>
<body>
<h1>{0}</h1>
<p>Drag to turn, scroll to zoom, right-drag to pan; the slider moves through the load steps. Opens from file:// with
no network (three.js is in {1}/).</p>
<div class="needlekit-views"></div>
<script src="{1}/three.min.js"></script>
<script src="{1}/OrbitControls.js"></script>
<script src="{1}/needlekit_viewer.js"></script>
{2}<script>needlekitViewer.mountAll(document.querySelector(".needlekit-views"));</script>
</body></html>
)",
                     xml_escaped(title), folder, data);
}

std::vector<std::pair<std::string, std::string>> viewer_files(const ViewerSources& sources) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const char* name : {"needlekit_viewer.js", "needlekit_viewer.css"}) {
    files.emplace_back(name, read_file_bytes(sources.viewer / name, "needlekit viewer file"));
  }
  for (const auto& [name, relative] : {std::pair{"three.min.js", "three.min.js"},
                                       std::pair{"OrbitControls.js", "examples/js/controls/OrbitControls.js"}}) {
    const std::filesystem::path path = sources.three / relative;
    try {
      files.emplace_back(name, read_file_bytes(path, "three.js file"));
    } catch (const IoError& error) {
      throw IoError(fmt::format("{} (the 3D views need Debian's libjs-three: scripts/install-deps)", error.what()));
    }
  }
  return files;
}

std::filesystem::path stage_view_page(StagedFiles& files, const std::filesystem::path& directory,
                                      const std::string& page, const std::string& title,
                                      const std::vector<std::string>& scripts, const ViewerFiles& viewer) {
  const std::filesystem::path folder = directory / kViewerFolder;
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw IoError(fmt::format("{}: cannot create the viewer folder: {}", folder.string(), error.message()));
  for (const auto& [name, content] : viewer) files.write(folder / name, content);
  files.write(directory / page, view_page(title, scripts));
  return directory / page;
}

}  // namespace needlekit::io
