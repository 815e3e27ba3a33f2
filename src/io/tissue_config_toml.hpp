// Internal to the io folder: the [tissue] and [mesh] tables of an already parsed case file, for the readers of
// files that contain them (tissue_config.cpp, the indentation case reader). Not installed.
#pragma once
#include <filesystem>
#include <string_view>

#include "needlekit/io/tissue_config.hpp"
#include "needlekit/io/toml_config.hpp"

namespace needlekit::io::config {

// Reads [tissue] and [mesh] of `root` (both optional; defaults as in tissue_config.hpp); a relative mesh file is
// resolved against `base_dir`. Throws InvalidInput naming FILE:LINE and the key.
TissueCase tissue_case_of(const toml::table& root, std::string_view file, const std::filesystem::path& base_dir);

}  // namespace needlekit::io::config
