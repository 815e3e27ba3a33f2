// Patch case files (`needlekit patch CASE.toml`), in TOML. Every dimensional value is a string with its unit; errors
// name FILE:LINE, the key, the value and what was expected.
//
//   [surface]  mesh = "path" (OBJ, STL, PLY or OFF; relative to the case file's folder);
//              unit = the length of one file unit: "m", "mm", or e.g. "15.8 mm" (required);
//              center_vertex = 0-based vertex index, or center = ["x mm", "y mm", "z mm"] (one of them);
//              rotation = "0 deg" (about the approach axis); approach (patch::kApproachNames, default "-z")
//   [patch]    kind (patch::kPatchKindNames); size = "10 mm" (side w); needles_per_row (>= 2);
//              spring_constant = "1 N/mm" or { u = "1 N/mm", v = "1 N/mm", diagonal = "1 N/mm" };
//              max_spring_energy = "0.05 mJ" (flexible); first_node (patch::kFirstNodeNames, default
//              "first-contact"); walk (patch::kWalkMethodNames, default "cutting-plane");
//              load = "0.0712 N" (equilibrium: force per node; default |F(A)| of the needle)
//   [needle], [tissue], [insertion]   as in design files (io/design_config.hpp)
#pragma once
#include <filesystem>
#include <string_view>

#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"
#include "needlekit/patch/patch_design.hpp"
#include "needlekit/patch/patch_placement.hpp"

namespace needlekit::io {

struct PatchCase {
  std::filesystem::path mesh;      // resolved against the case file's folder
  double mesh_unit = 1;            // m per file unit
  patch::Placement placement;
  patch::PatchDesignOptions design;
  patch::FitOptions fit;
  bool load_given = false;         // [patch].load was given (else the equilibrium load is |F(A)|)
  patch::NeedleEvaluationOptions evaluation;
};

// A body surface as a case's [surface] table names it, mesh and unit only (`needlekit serve` draws the body before a
// patch is placed on it: io/json_config.hpp).
struct BodyMeshFile {
  std::filesystem::path mesh;      // resolved against the case file's folder
  double mesh_unit = 1;            // m per file unit
};

// Throws IoError (unreadable file, TOML syntax) or InvalidInput (a missing, unknown or invalid key).
PatchCase read_patch_case(const std::filesystem::path& path);
// The same from text; `source_name` stands for the file in messages, `base_folder` resolves the mesh path.
// `uncertainty_tables` also allows [uncertain], [sampling] and [[correlation]] (io/patch_uncertainty_config.hpp reads
// them).
PatchCase parse_patch_case_toml(std::string_view text, std::string_view source_name,
                                const std::filesystem::path& base_folder, bool uncertainty_tables = false);

}  // namespace needlekit::io
