// The input-file formats with units and valid ranges, shown at the end of the commands' --help. Every list of
// choices is generated from the enum tables (core/enum_table.hpp) and preset lists that the readers use, so the help
// names exactly the values the readers accept (tests/example/test_help_choices.cpp checks it).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/parameter_text.hpp"

namespace needlekit::cli {

std::string design_file_help();      // evaluate, sweep, mesh
std::string space_file_help();       // optimize
std::string indentation_case_help(); // indent (and, by reference, insert)
std::string patch_case_help();       // patch
// The rows of `group` ("loading") of a parameter table's texts one per line, "key = default   range: meaning" ("key
// (required)" for a required row), the first headed by `label` ("  [loading]"), each key at column `indent` or past
// the label.
std::string settings_help(const std::vector<ParameterText>& texts, std::string_view group, std::string_view label,
                          std::size_t indent = 15);
// The rows of group "tissue" or "mesh" of mesh::kLayeredBlockParameters, one per line with default, range and
// meaning, the first headed by `label` ("  [mesh]"): tissue-mesh and indent.
std::string block_settings_help(std::string_view group, std::string_view label);

inline constexpr const char* kRobustSpaceHelp = R"(Robust design (optional): add
  min_success_probability = 0.99 the best nominal design whose P(success) under [uncertain] is at least this
  [uncertain], [sampling], [[correlation]]   as in `needlekit uncertainty --help`; a design variable (tip_diameter,
                                 base_diameter, bore_diameter, length, width) takes no mean: its spread is centred
                                 on every candidate. The best max 2000 nominal designs are checked, best first.)";

// The uncertainty file's own tables: [uncertain], [sampling] (from uncertainty::kPropagationParameters) and
// [[correlation]].
std::string uncertainty_file_help();
// The puncture-force laws of [tissue] puncture_force, from the law table (analysis::kPunctureForceLawKindNames).
std::string puncture_force_law_help();

}  // namespace needlekit::cli
