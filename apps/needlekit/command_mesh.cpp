// `needlekit mesh DESIGN.toml --out needle.stl`: the closed surface mesh of the design's needle, as binary STL.
#include <fmt/format.h>

#include <memory>
#include <string>

#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

namespace needlekit::cli {
namespace {

struct MeshArguments {
  std::string design_path;
  std::string out_path;
  std::string unit = "um";
  int circumferential_segments = 64;
  int axial_segments = 16;
};

void run_mesh(const MeshArguments& arguments) {
  const io::DesignFile file = io::read_design_file(arguments.design_path);
  const double unit = units::unit_factor(arguments.unit, units::Dimension::Length, "--unit");
  needle::NeedleMeshOptions options;
  options.circumferential_segments = arguments.circumferential_segments;
  options.axial_segments = arguments.axial_segments;
  const geometry::TriangleMesh mesh = needle::needle_surface_mesh(file.design.needle, options);
  geometry::write_stl(mesh, arguments.out_path, 1.0 / unit);
  const double analytic = needle::volume(file.design.needle);
  const double meshed = geometry::signed_volume(mesh);
  fmt::print("wrote {}: {} triangles, {} vertices, coordinates in {} (axis z, base at z = 0, tip at z = L)\n",
             arguments.out_path, mesh.triangles.size(), mesh.vertices.size(), arguments.unit);
  fmt::print("volume: mesh {:.6g} um^3, analytic {:.6g} um^3 (relative difference {:.2e})\n", meshed * 1e18,
             analytic * 1e18, meshed / analytic - 1);
}

}  // namespace

void add_mesh_command(CLI::App& app) {
  auto arguments = std::make_shared<MeshArguments>();
  CLI::App* command = app.add_subcommand(
      "mesh", "Closed, outward-oriented triangle surface mesh of the design's needle, written as binary STL");
  command->add_option("DESIGN", arguments->design_path, "design file (TOML); only [needle] is used")->required();
  command->add_option("--out", arguments->out_path, "STL file to write (written only on success)")
      ->type_name("FILE")
      ->required();
  command->add_option("--unit", arguments->unit, "length unit of the STL coordinates: nm, um, mm, cm or m")
      ->default_val("um");
  command->add_option("--segments", arguments->circumferential_segments,
                      "segments around the axis, >= 8 (volume error ~ 1.5e-3 at 64, second order)")
      ->default_val(64)
      ->check(CLI::Range(8, 1 << 16));
  command->add_option("--axial-segments", arguments->axial_segments, "segments along the length, >= 1")
      ->default_val(16)
      ->check(CLI::Range(1, 1 << 16));
  command->footer(design_file_help());
  command->callback([arguments] { run_mesh(*arguments); });
}

}  // namespace needlekit::cli
