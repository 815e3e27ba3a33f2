// Internal to the io folder: the readers of design, design-space and uncertainty files from an already parsed TOML
// table, so that a file read from TOML text (design_config.cpp, uncertainty_config.cpp) and one converted from JSON
// (json_config.cpp, the `needlekit serve` API) go through the same code and give the same messages. Not installed.
#pragma once
#include <toml++/toml.h>

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include "needlekit/io/design_config.hpp"
#include "needlekit/io/json_config.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/io/uncertainty_config.hpp"

namespace needlekit::io::config {

// A design file's root table ([needle], [array], [tissue], [insertion]); `file` names the source in messages.
DesignFile design_of_table(const toml::table& root, const std::string& file);
// The design tables of a root that also holds `other_tables` (read by the caller); any other table is an error.
DesignFile design_of_tables(const toml::table& root, const std::string& file,
                            std::initializer_list<std::string_view> other_tables, bool with_array);
// A design-space file's root table.
SpaceFile space_of_table(const toml::table& root, const std::string& file);
// A patch case's root table; `base_folder` resolves [surface] mesh (the caller checks what it names).
PatchCase patch_case_of_table(const toml::table& root, const std::string& file,
                              const std::filesystem::path& base_folder, bool uncertainty_tables);
// A root table holding only [surface] with mesh and unit; `base_folder` resolves the mesh (the caller checks it).
BodyMeshFile body_mesh_of_table(const toml::table& root, const std::string& file,
                                const std::filesystem::path& base_folder);
// A root table holding [surface] (mesh, unit) and [ray] (origin, direction): a click on the body's view.
BodyPick body_pick_of_table(const toml::table& root, const std::string& file, const std::filesystem::path& base_folder);
// An uncertainty file's root table (a design file plus [uncertain], [sampling], [[correlation]]).
UncertaintyFile uncertainty_of_table(const toml::table& root, const std::string& file);

}  // namespace needlekit::io::config
