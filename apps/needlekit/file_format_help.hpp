// The input-file formats with units and valid ranges, shown at the end of the commands' --help. Every list of
// choices is generated from the enum tables (core/enum_table.hpp) and preset lists that the readers use, so the help
// names exactly the values the readers accept (tests/example/test_help_choices.cpp checks it).
#pragma once
#include <string>

namespace needlekit::cli {

std::string design_file_help();      // evaluate, sweep, mesh
std::string space_file_help();       // optimize
std::string indentation_case_help(); // indent (and, by reference, insert)
std::string patch_case_help();       // patch

}  // namespace needlekit::cli
