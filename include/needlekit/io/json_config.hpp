// Design, design-space and uncertainty files given as JSON (the `needlekit serve` API, docs/serve.md): the same keys,
// unit strings, defaults and checks as their TOML files (io/design_config.hpp, io/uncertainty_config.hpp), because
// the JSON is converted to a TOML table and read by the same reader. A JSON object is a TOML table, an array an
// array, a string a string, an integer an integer, a number with a fraction or exponent a float, true/false a
// boolean; null has no TOML value and is an error naming its key.
//
// Messages are the TOML reader's, with `source_name` for the file and line 1 (a JSON value has no line of its own):
//   design.json:1: key 'needle.tip_diameter': '-30 um' is not positive, expected a positive length
#pragma once
#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "needlekit/io/design_config.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/io/uncertainty_config.hpp"

namespace needlekit::io {

// Throw IoError for text that is not JSON or not a JSON object, InvalidInput for what the TOML reader refuses.
DesignFile parse_design_json(std::string_view text, std::string_view source_name);
SpaceFile parse_space_json(std::string_view text, std::string_view source_name);
UncertaintyFile parse_uncertainty_json(std::string_view text, std::string_view source_name);

// A patch case (io/patch_config.hpp) whose [surface] mesh is a key of `meshes` (a name -> the file, whose file name is
// that name): any other string (a path, "../x") is InvalidInput naming surface.mesh and the names offered, so no other
// file is ever opened.
PatchCase parse_patch_case_json(std::string_view text, std::string_view source_name,
                                const std::map<std::string, std::filesystem::path>& meshes);

// {"surface": {"mesh": a key of `meshes`, "unit": "1 mm"}}: the body surface a patch case would name (the same keys,
// checks and messages as its [surface] table), for the body's view before the patch is placed.
BodyMeshFile parse_body_mesh_json(std::string_view text, std::string_view source_name,
                                  const std::map<std::string, std::filesystem::path>& meshes);

// {"surface": {"mesh": a key of `meshes`, "unit": "1 mm"}, "ray": {"origin": ["x m", "y m", "z m"], "direction":
// [dx, dy, dz]}}: a click on the body's view, as the camera's ray through the clicked pixel in the mesh's
// coordinates (metres once scaled by the unit); the direction's length does not matter.
struct BodyPick {
  BodyMeshFile body;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();     // m
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // non-zero
};
BodyPick parse_body_pick_json(std::string_view text, std::string_view source_name,
                              const std::map<std::string, std::filesystem::path>& meshes);

}  // namespace needlekit::io
