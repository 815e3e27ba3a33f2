// `needlekit tissue-mesh CASE.toml --out DIR`: the layered tissue block of a case file's [tissue] and [mesh] tables,
// meshed with Gmsh into linear tetrahedra and written as DIR/tissue.vtu (layer, E, nu, quality per element), with
// the element count and quality of each layer.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "terminal_warnings.hpp"
#include "file_format_help.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/tet_mesh_vtu.hpp"
#include "needlekit/io/tissue_config.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"

namespace needlekit::cli {
namespace {

// [tissue]'s width and length and [mesh]'s sizes come from mesh::kLayeredBlockParameters (block_settings_help).
constexpr const char* kTissueFileHelp = R"(CASE file (TOML; other tables such as [needle] or [loading] are ignored):
{}            (block centred on x = y = 0, top surface z = 0)
            preset = "skin" | "skin-stiff-sc" | "silicone-0.2mpa" | "silicone-0.5mpa" | "skin-geerligs-2011"
            or, top to bottom:
            [[tissue.layers]]  name = "stratum corneum", thickness = "20 um", youngs_modulus = "100 MPa",
                               poisson_ratio = 0.4   (the last layer may have thickness = "rest")
            height = "1150 um"                        (optional; the block height that "rest" fills)
{}            sites = [["0 um", "0 um"]]
            or file = "tissue.msh", unit = "um"  (a tetrahedral Gmsh mesh whose physical volumes are named after
            the layers, top surface at z = 0; layer thicknesses are then not used))";

struct TissueMeshArguments {
  std::string case_path;
  std::string out_dir;
  int threads = 0;
  bool json = false;
};

void run_tissue_mesh(const TissueMeshArguments& arguments) {
  io::TissueCase tissue = io::read_tissue_case(arguments.case_path);
  print_warnings(tissue.warnings);
  tissue.block.threads = arguments.threads;
  const mesh::LayeredBlockOptions& options = tissue.block;
  create_output_directory(arguments.out_dir);  // before meshing: a directory that cannot be written fails fast
  const mesh::LayeredBlockResult result = io::tissue_mesh(tissue);
  throw_if_interrupted();  // Gmsh cannot be stopped midway: Ctrl-C during meshing ends here, nothing written
  const std::filesystem::path file = std::filesystem::path(arguments.out_dir) / "tissue.vtu";
  io::write_vtu(io::tet_mesh_grid(result.mesh), file);

  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const auto& p : result.mesh.nodes) low = low.cwiseMin(p), high = high.cwiseMax(p);
  const Eigen::Vector3d extent = high - low;
  if (arguments.json) {
    nlohmann::json layers = nlohmann::json::array();
    for (std::size_t i = 0; i < result.quality.size(); ++i) {
      const mesh::TissueLayer& l = result.mesh.layers[i];
      const mesh::LayerQuality& q = result.quality[i];
      const nlohmann::json thickness = tissue.msh_file.empty() ? nlohmann::json(l.thickness * 1e6) : nlohmann::json();
      layers.push_back({{"name", l.name}, {"thickness_um", thickness},
                        {"youngs_modulus_MPa", l.youngs_modulus * 1e-6}, {"poisson_ratio", l.poisson_ratio},
                        {"elements", q.tets}, {"min_quality", q.min_quality}, {"mean_quality", q.mean_quality}});
    }
    const nlohmann::json out = {{"width_um", extent.x() * 1e6}, {"length_um", extent.y() * 1e6},
                                {"height_um", extent.z() * 1e6},   {"elements", result.mesh.tets.size()},
                                {"nodes", result.mesh.nodes.size()}, {"mesh_seconds", result.mesh_seconds},
                                {"layers", layers},                {"file", file.string()}};
    fmt::print("{}", io::json_text(out));
    return;
  }
  if (tissue.msh_file.empty()) {
    fmt::print("tissue block {:g} x {:g} x {:g} um, {} insertion site(s): ", extent.x() * 1e6, extent.y() * 1e6,
               extent.z() * 1e6, options.insertion_sites.size());
  } else {
    fmt::print("{} ({:g} x {:g} x {:g} um): ", tissue.msh_file.string(), extent.x() * 1e6, extent.y() * 1e6,
               extent.z() * 1e6);
  }
  fmt::print("{} tetrahedra, {} nodes, in {:.2f} s\n", result.mesh.tets.size(), result.mesh.nodes.size(),
             result.mesh_seconds);
  fmt::print("{:<20} {:>12} {:>10} {:>6} {:>10} {:>12} {:>13}\n", "layer", "thickness_um", "E_MPa", "nu", "elements",
             "min_quality", "mean_quality");
  for (std::size_t i = 0; i < result.quality.size(); ++i) {
    const mesh::TissueLayer& l = result.mesh.layers[i];
    const mesh::LayerQuality& q = result.quality[i];
    const std::string thickness = tissue.msh_file.empty() ? fmt::format("{:.6g}", l.thickness * 1e6) : "-";
    fmt::print("{:<20} {:>12} {:>10.6g} {:>6.3g} {:>10} {:>12.3f} {:>13.3f}\n", l.name, thickness,
               l.youngs_modulus * 1e-6, l.poisson_ratio, q.tets, q.min_quality, q.mean_quality);
  }
  fmt::print("wrote {}\n", file.string());
}

}  // namespace

void add_tissue_mesh_command(CLI::App& app) {
  auto arguments = std::make_shared<TissueMeshArguments>();
  CLI::App* command = app.add_subcommand(
      "tissue-mesh", "Mesh the layered tissue block of a case file (Gmsh, linear tetrahedra) and write it as VTU");
  command->add_option("CASE", arguments->case_path, "case file (TOML); [tissue] and [mesh] are used")->required();
  command->add_option("--out", arguments->out_dir, "folder for tissue.vtu (created if missing; written on success)")
      ->type_name("DIR")
      ->required();
  command->add_option("--threads", arguments->threads, "Gmsh threads, 0 = one (the same mesh in every run); N > 1 meshes surfaces on N threads, not reproducibly")
      ->default_val(0)
      ->check(CLI::Range(0, 1024));
  command->add_flag("--json", arguments->json, "print the mesh summary as JSON (units in the key names)");
  command->footer(fmt::format(kTissueFileHelp, block_settings_help("tissue", "  [tissue]"),
                              block_settings_help("mesh", "  [mesh]")));
  command->callback([arguments] { run_tissue_mesh(*arguments); });
}

}  // namespace needlekit::cli
