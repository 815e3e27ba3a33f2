// The [tissue] and [mesh] tables of a case file (TOML), shared by `needlekit tissue-mesh` and the indentation case
// (`needlekit indent`). Other top-level tables are not looked at here. Errors name FILE:LINE and the key.
//
//   [tissue]  width, length (default "3000 um" each, centred on x = y = 0; the top surface is z = 0);
//             preset = a tissue preset name (materials::tissue_preset_names()), or [[tissue.layers]] entries, top to
//             bottom, with name, thickness (a length, or "rest" for the last layer: height minus the others),
//             youngs_modulus (a pressure), poisson_ratio (a number in (-1, 0.5), default 0.4); neither: "skin";
//             height (default: the preset's, or "1150 um" with "rest"; with explicit thicknesses it must equal
//             their sum if given).
//   [mesh]    size_at_tip (default "20 um"), size_far (default "250 um"), refinement_radius (default "300 um"),
//             size_gradient (number, default 0.3), thin_layer_size_factor (number >= 0, default 2),
//             sites = [["-800 um", "-800 um"], ...] (insertion sites (x, y); default one at the centre),
//             site_circle_radius (a circle of nodes around each site, e.g. a flat punch's edge; default none);
//             or file = "tissue.msh" (a user's tetrahedral Gmsh mesh, relative to the case file, whose physical volume
//             groups are named after the [[tissue.layers]]; its top surface must be z = 0) and unit (the file's
//             length unit, default "um"); max_tetrahedra (default 5e7, core/limits.hpp): a block whose estimated
//             tetrahedron count is larger is refused before meshing.
#pragma once
#include <filesystem>
#include <string>
#include <vector>
#include <string_view>

#include "needlekit/mesh/layered_block_mesh.hpp"

namespace needlekit::io {

struct TissueCase {
  mesh::LayeredBlockOptions block;    // the block to mesh; with msh_file, its layers name the file's volumes
  std::filesystem::path msh_file;     // [mesh] file, resolved against the case file's folder; empty: mesh `block`
  double msh_unit = 1e-6;             // m per length unit of msh_file ([mesh] unit)
  // Tables of the file that a tissue case does not read but a reader of whole cases would ([array]: the block of an
  // array), each with FILE:LINE: `needlekit tissue-mesh` prints them as warnings.
  std::vector<std::string> warnings;
};

// Throws IoError (unreadable file, TOML syntax) or InvalidInput (an unknown, missing or invalid key).
TissueCase read_tissue_case(const std::filesystem::path& path);
// The same from text; `source_name` stands for the file name in messages, `base_dir` resolves a relative mesh file.
TissueCase parse_tissue_case_toml(std::string_view text, std::string_view source_name,
                                  const std::filesystem::path& base_dir = {});

// The tissue mesh of a case: the meshed block, or the imported .msh with the case's layers (per-layer quality,
// meshing/reading time). Throws InvalidInput naming the .msh for a file whose top is not z = 0, or as msh_import.
mesh::LayeredBlockResult tissue_mesh(const TissueCase& tissue);

// Only the block of a case without a mesh file (throws InvalidInput if [mesh] has a file).
mesh::LayeredBlockOptions read_tissue_block(const std::filesystem::path& path);
// The same from text; `source_name` stands for the file name in messages.
mesh::LayeredBlockOptions parse_tissue_block_toml(std::string_view text, std::string_view source_name);

}  // namespace needlekit::io
