// Internal to the io folder: the [tissue] and [mesh] tables of an already parsed case file, for the readers of
// files that contain them (tissue_config.cpp, the indentation case reader). Not installed.
#pragma once
#include <string_view>

#include "needlekit/mesh/layered_block_mesh.hpp"
#include "toml_config.hpp"

namespace needlekit::io::config {

// Reads [tissue] and [mesh] of `root` (both optional; defaults as in tissue_config.hpp). Throws InvalidInput naming
// FILE:LINE and the key.
mesh::LayeredBlockOptions tissue_block_of(const toml::table& root, std::string_view file);

}  // namespace needlekit::io::config
