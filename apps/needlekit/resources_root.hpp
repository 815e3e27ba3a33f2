// Where the tool finds the files of the needlekit tree it needs at run time (reproduce: docs/published and
// scripts/report.py; serve: web/design): $NEEDLEKIT_ROOT, the install prefix's share/needlekit, or the source tree
// this tool was built from, the first that holds every one of `files` (paths relative to the tree).
#pragma once
#include <filesystem>
#include <initializer_list>
#include <string_view>

namespace needlekit::cli {

// Throws IoError naming the files and the places searched.
std::filesystem::path resources_root(std::initializer_list<std::string_view> files);

}  // namespace needlekit::cli
