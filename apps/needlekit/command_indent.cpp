// `needlekit indent CASE.toml [--json] [--out DIR]`: push one or several rigid needles into a layered tissue block
// with the nonlinear FE solver and report the force-depth curve and the puncture point (dissertation §3.4-3.5, 6.2).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/indentation_output.hpp"
#include "progress_bar.hpp"

namespace needlekit::cli {
namespace {

constexpr const char* kCaseFileHelp = R"(CASE file (TOML; every dimensional value is a string with its unit, a bare number is an error):
  name = "flat punch"                optional, names the output files (default: the file name)
  [needle]     shape, tip_diameter, base_diameter, bore_diameter, length as in design files (material is ignored:
               the needle is rigid), or mesh = "needle.stl" + mesh_unit = "um" (needle frame: axis z, tip at max z)
               tip_height = "0 um"       >= 0, the tip's height above the surface at the start
  [[needles]]  x = "-800 um", y = "-800 um", tip_height   one entry per needle (default: one needle at 0, 0)
  [tissue]     width = "3000 um", length = "3000 um", height (default: sum of the layers), preset = "skin" |
               "silicone-0.2mpa" | ... or [[tissue.layers]] name, thickness (the last may be "rest"),
               youngs_modulus = "0.2 MPa", poisson_ratio = 0.49 (in (-1, 0.5))
  [mesh]       size_at_tip = "20 um", size_far = "250 um", refinement_radius = "300 um", sites = [["x", "y"], ...]
               (one needle per site without [[needles]]), split = true (mesh at twice the sizes and split every tet
               into eight: the two-grid solver, for large meshes), or file = "tissue.msh" + unit (layers = physical
               groups)
  [loading]    depth = "200 um" (required), steps = 20, continue_after_puncture = false
  [model]      law = "neo-hookean" | "svk", contact = "surface" | "tip-nodes", element = "linear" | "quadratic",
               boundary = "sides-and-bottom-fixed" | "bottom-fixed" | "bottom-fixed-sides-roller"
  [solver]     optional: residual_tolerance = 1e-6, displacement_tolerance = 1e-5, energy_tolerance = 1e-8,
               max_iterations = 25, max_cutbacks = 8, predictor = "secant" | "linearised", linear_solver = "auto" |
               "two-grid" | "cholesky-cg" | "cholesky", volumetric = "auto" | "element" | "nodal-average" (auto: linear
               tetrahedra of layers with poisson_ratio >= 0.45 average the volume at the nodes, locking-free),
               penalty_factor = 100, threads = 0
  [puncture]   critical_pressure = "0.663 MPa" and/or toughness = "100 J/m2" or toughness_from = { first = "a.csv",
               second = "b.csv", crack_area = "6661 um2" } (Eq 3.16 from two insertions; CSV depth_um,force_N))";

struct IndentArguments {
  std::string case_path;
  std::string out_dir;
  bool json = false;
  std::string size_at_tip;
  std::string size_far;
  std::string depth;
  int steps = 0;
};

void run_indent(const IndentArguments& arguments) {
  insertion::IndentationCase indentation_case = io::read_indentation_case(arguments.case_path);
  // Command-line overrides (a quick mode for tests and sweeps: coarser mesh, fewer steps).
  if (!arguments.size_at_tip.empty()) {
    indentation_case.block.size_at_site =
        units::parse_quantity(arguments.size_at_tip, units::Dimension::Length, "--size-at-tip");
    indentation_case.block.size_far = std::max(indentation_case.block.size_far, indentation_case.block.size_at_site);
  }
  if (!arguments.size_far.empty()) {
    indentation_case.block.size_far = units::parse_quantity(arguments.size_far, units::Dimension::Length, "--size-far");
  }
  if (!arguments.depth.empty()) {
    indentation_case.depth = units::parse_quantity(arguments.depth, units::Dimension::Length, "--depth");
  }
  if (arguments.steps > 0) indentation_case.steps = arguments.steps;
  insertion::validate(indentation_case);

  std::optional<io::IndentationWriter> writer;
  if (!arguments.out_dir.empty()) writer.emplace(arguments.out_dir, indentation_case);

  ProgressBar progress(fmt::format("indent {}", indentation_case.name));
  insertion::IndentationOptions options;
  options.progress = [&progress](const insertion::IndentationProgress& p) { progress.update(p.fraction); };
  if (writer) {
    options.on_mesh = [&writer](const mesh::TetMesh& tissue) { writer->set_mesh(tissue); };
    options.on_step = [&writer](const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
      writer->write_step(step, solver);
    };
  }
  const insertion::IndentationResult result = insertion::run_indentation(indentation_case, options);
  progress.finish();
  if (writer) writer->finish(result);
  // A run that stopped on a numerical failure ends with its own exit code, after everything it kept is written and
  // printed.
  const auto outcome = [&result] {
    if (result.status == insertion::IndentationStatus::SolverFailed) throw CommandOutcome{ExitCode::NumericalFailure};
  };

  if (arguments.json) {
    fmt::print("{}\n", io::indentation_json(indentation_case, result).dump(2));
    outcome();
    return;
  }
  fmt::print("{}: {} tetrahedra, {} nodes, {} unknowns ({} solver); mesh {:.2f} s, total {:.2f} s\n",
             indentation_case.name, result.elements, result.nodes, result.dofs, fem::to_string(result.linear_solver),
             result.mesh_seconds, result.total_seconds);
  fmt::print("models: {}\n", io::fe_models_text(indentation_case.solver));
  fmt::print("{:>10} {:>12} {:>14} {:>10}\n", "depth_um", "force_N", "pressure_MPa", "newton");
  for (const insertion::IndentationStep& step : result.steps) {
    fmt::print("{:>10.4g} {:>12.5g} {:>14.5g} {:>10}\n", step.depth * 1e6, step.force, step.contact_pressure * 1e-6,
               step.newton_iterations);
  }
  if (result.puncture) {
    fmt::print("puncture: depth {:.4g} um, force {:.5g} N ({})\n", result.puncture->depth * 1e6,
               result.puncture->force, insertion::to_string(result.puncture->criterion));
  } else {
    fmt::print("puncture: none\n");
  }
  fmt::print("status: {}: {}\n", insertion::to_string(result.status), result.reason);
  if (writer) {
    // Name the ParaView series only when it was written (a run that fails in its first step writes no step).
    const std::filesystem::path series = std::filesystem::path(arguments.out_dir) / (indentation_case.name + ".pvd");
    const auto& files = writer->files();
    const bool has_series = std::find(files.begin(), files.end(), series) != files.end();
    fmt::print("wrote {} files to {}{}\n", files.size(), arguments.out_dir,
               has_series ? fmt::format(" (open {} in ParaView)", series.filename().string()) : std::string());
  }
  outcome();
}

}  // namespace

void add_indent_command(CLI::App& app) {
  auto arguments = std::make_shared<IndentArguments>();
  CLI::App* command = app.add_subcommand(
      "indent", "Nonlinear FE indentation of a layered tissue block by rigid needles, up to puncture (§3.4-3.5)");
  command->add_option("CASE", arguments->case_path, "indentation case file (TOML)")->required();
  command->add_option("--out", arguments->out_dir,
                      "directory for the ParaView series (.pvd/.vtu per step), force-depth and solver CSV, JSON")
      ->type_name("DIR");
  command->add_flag("--json", arguments->json, "print the result as one JSON object (units in the key names)");
  command->add_option("--size-at-tip", arguments->size_at_tip, "override [mesh] size_at_tip, e.g. \"60 um\"");
  command->add_option("--size-far", arguments->size_far, "override [mesh] size_far, e.g. \"400 um\"");
  command->add_option("--depth", arguments->depth, "override [loading] depth, e.g. \"50 um\"");
  command->add_option("--steps", arguments->steps, "override [loading] steps")->check(CLI::Range(1, 100000));
  command->footer(kCaseFileHelp);
  command->callback([arguments] { run_indent(*arguments); });
}

}  // namespace needlekit::cli
