// The licence and attribution of a body surface mesh, as the README.md beside it states them: its section whose
// title contains "attribution" lists one bullet per mesh (or family of meshes, `skull_yahoojapan_*.obj`) with the
// source, the authors and the licence, and may end with lines such as where the licence texts are. Outputs made
// from a mesh (patch's surface.vtu, the report's figures) carry these lines (CC BY requires it).
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace needlekit::io {

struct MeshAttribution {
  std::filesystem::path readme;      // the README.md it was read from
  std::vector<std::string> entries;  // the bullets that name the mesh, each joined into one line; a bullet that
                                     // says "the same attribution" comes with the bullet before it
  std::vector<std::string> notices;  // the section's other lines (e.g. "License notices: `licenses/`.")
};

// The attribution of `mesh`; nullopt when there is no README.md beside it or no bullet of its attribution section
// names the mesh's file (a `*` in a name matches any characters).
std::optional<MeshAttribution> mesh_attribution(const std::filesystem::path& mesh);

// The warning for a mesh without one (for notes and the terminal).
std::string missing_attribution_warning(const std::filesystem::path& mesh);

}  // namespace needlekit::io
