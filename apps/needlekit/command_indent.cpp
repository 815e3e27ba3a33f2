// `needlekit indent CASE.toml [--json] [--out DIR]`: push one or several rigid needles into a layered tissue block
// with the nonlinear FE solver and report the force-depth curve and the puncture point (dissertation §3.4-3.5, 6.2).
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "child_process.hpp"
#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/fem/parallel_session.hpp"
#include "needlekit/io/indentation_output.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/scale_warnings.hpp"
#include "progress_bar.hpp"
#include "terminal_warnings.hpp"
#include "viewer_sources.hpp"

namespace needlekit::cli {
namespace {

struct IndentArguments {
  std::string case_path;
  std::string out_dir;
  bool json = false;
  bool no_plot = false;
  bool newton_log = false;
  std::string size_at_tip;
  std::string size_far;
  std::string depth;
  int steps = 0;
  std::string angle;
  std::string azimuth;
};

std::string needle_map_script() {
  if (const char* path = std::getenv("NEEDLEKIT_NEEDLE_MAP_SCRIPT")) return path;
  return std::string(NEEDLEKIT_SCRIPTS_DIR) + "/plot_needle_map.py";
}

// DIR/NAME_needle_map.png from NAME_needles.csv (scripts/plot_needle_map.py writes it under a temporary name).
std::filesystem::path write_needle_map(const std::filesystem::path& directory, const insertion::IndentationCase& c) {
  const std::filesystem::path png = directory / (c.name + "_needle_map.png");
  if (run_program({"/usr/bin/python3", needle_map_script(), (directory / (c.name + "_needles.csv")).string(),
                   png.string(), "--title", c.name}) != 0) {
    throw IoError(fmt::format("{}: the plot script {} failed (is python3-matplotlib installed? --no-plot skips the "
                              "plot)",
                              png.string(), needle_map_script()));
  }
  return png;
}

// The array's totals and which needles punctured, for the text output.
void print_array(const insertion::IndentationCase& c, const insertion::IndentationResult& result) {
  const insertion::ArrayOutcome& array = *result.array;
  fmt::print("array: {} x {} {} at pitch {:.4g} um (symmetry {}){}; {:.4g} % punctured at the last step\n",
             c.array->rows, c.array->columns, name_of(insertion::kArrayLayoutNames, c.array->layout),
             c.array->pitch * 1e6, name_of(insertion::kArraySymmetryNames, c.array->symmetry),
             c.array->backing_plate ? ", backing plate" : "",
             100 * (array.punctured_fraction.empty() ? 0.0 : array.punctured_fraction.back()));
  if (array.first_puncture_travel) fmt::print("first puncture at plate travel {:.4g} um\n", *array.first_puncture_travel * 1e6);
  fmt::print("inserted depth: mean {:.4g} um, spread {:.4g} um ({:.3g} % of the needle's length)\n",
             array.mean_inserted_depth * 1e6, array.inserted_depth_spread * 1e6, 100 * array.mean_penetrated_fraction);
}

// The run as text: the mesh, the models, every step, the puncture, the array's totals, the angled insertion's loads
// and the bending check.
void print_result(const insertion::IndentationCase& indentation_case, const insertion::IndentationResult& result) {
  fmt::print("{}: {} tetrahedra, {} nodes, {} unknowns ({} solver); mesh {:.2f} s, total {:.2f} s\n",
             indentation_case.name, result.elements, result.nodes, result.dofs,
             indentation_case.solver.backend == fem::SolverBackend::Petsc ? std::string("petsc")
                                                                          : fem::to_string(result.linear_solver),
             result.mesh_seconds, result.total_seconds);
  fmt::print("models: {}\n", io::fe_models_text(indentation_case));
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
  if (result.array) print_array(indentation_case, result);
  if (indentation_case.angle > 0 && !result.steps.empty()) {
    const insertion::IndentationStep& last = result.steps.back();
    fmt::print("angled insertion ({:.4g} deg from the normal, azimuth {:.4g} deg), last step: axial {:.5g} N, lateral "
               "({:.5g}, {:.5g}) N, moment about the base {:.5g} N m\n",
               indentation_case.angle * 180 / M_PI, indentation_case.azimuth * 180 / M_PI, last.force,
               last.lateral_force.x(), last.lateral_force.y(), last.moment.norm());
  }
  if (result.bending) {
    fmt::print("bending (Eqs 5.7/5.8): lateral load {:.5g} N, critical {:.5g} N, margin {:.4g}\n",
               result.bending->lateral_load, result.bending->critical_load, result.bending->margin);
  }
}

// The case file with the command line's overrides (a quick mode for tests and sweeps: coarser mesh, fewer steps).
insertion::IndentationCase read_case(const IndentArguments& arguments) {
  insertion::IndentationCase indentation_case = io::read_indentation_case(arguments.case_path);
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
  if (!arguments.angle.empty()) {
    indentation_case.angle = units::parse_quantity(arguments.angle, units::Dimension::Angle, "--angle");
  }
  if (!arguments.azimuth.empty()) {
    indentation_case.azimuth = units::parse_quantity(arguments.azimuth, units::Dimension::Angle, "--azimuth");
  }
  insertion::validate(indentation_case);
  return indentation_case;
}

void run_indent(const IndentArguments& arguments) {
  insertion::IndentationCase indentation_case = read_case(arguments);
  if (arguments.newton_log && fem::process_rank() == 0) {
    // One line per Newton iteration on stderr (rank 0), for following a long run and finding its hard steps.
    indentation_case.solver.progress = [](const fem::SolverProgress& p) {
      fmt::print(stderr,
                 "newton: target {:.6g} um, augmentation {}, iteration {}: residual {:.4g} N, cut-backs {}, step "
                 "length {:.4g}, CG {}{}\n",
                 p.target_displacement * 1e6, p.augmentation, p.iteration, p.residual_norm, p.cutbacks, p.step_length,
                 p.linear_iterations, p.contact_set_changed ? ", contact changed" : "");
    };
  }
  if (fem::process_rank() == 0) print_warnings(io::indentation_scale_warnings(indentation_case));  // once under mpirun

  std::optional<io::IndentationWriter> writer;
  // Under mpirun every rank runs the case; rank 0 alone writes the files.
  if (!arguments.out_dir.empty() && fem::process_rank() == 0) {
    writer.emplace(arguments.out_dir, indentation_case);
    writer->write_view(viewer_sources());
  }

  ProgressBar progress(fmt::format("indent {}", indentation_case.name));
  insertion::IndentationOptions options;
  options.progress = [&progress](const insertion::IndentationProgress& p) { progress.update(p.fraction); };
  // Each rezoning is reported when it happens (a long run's only sign of it), once under mpirun; the other notes at
  // the end.
  options.on_remesh = [&writer, &progress](const insertion::Remesh& remesh) {
    if (fem::process_rank() != 0) return;
    progress.break_line();
    print_warnings({io::remesh_note(remesh)});
    if (writer) writer->add_remesh(remesh);
  };
  if (writer) {
    options.on_mesh = [&writer](const mesh::TetMesh& tissue) { writer->set_mesh(tissue); };
    options.on_step = [&writer](const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
      writer->write_step(step, solver);
    };
  }
  const insertion::IndentationResult result = insertion::run_indentation(indentation_case, options);
  progress.finish();
  if (fem::process_rank() == 0) print_warnings(io::deformation_notes(indentation_case, result));
  if (writer) writer->finish(result);
  if (writer && result.array && !arguments.no_plot) {
    writer->remember(write_needle_map(arguments.out_dir, indentation_case));
  }
  // A load step that did not converge: the completed steps are kept and printed, the exit code is 3.
  const bool failed = result.status == insertion::IndentationStatus::SolverFailed;
  if (arguments.json) {
    fmt::print("{}", io::json_text(io::indentation_json(indentation_case, result)));
    if (failed) throw CommandOutcome{ExitCode::NumericalFailure};
    return;
  }
  print_result(indentation_case, result);
  fmt::print("status: {}: {}\n", insertion::to_string(result.status), result.reason);
  if (writer) {
    const bool series = !result.steps.empty();  // the .pvd exists once a step was written
    fmt::print("wrote {} files to {}{}\n", writer->files().size(), arguments.out_dir,
               series ? fmt::format(" (open {0}.pvd in ParaView, {0}_view.html in a browser)", indentation_case.name)
                      : "");
  }
  if (failed) throw CommandOutcome{ExitCode::NumericalFailure};
}

}  // namespace

void add_indent_command(CLI::App& app) {
  auto arguments = std::make_shared<IndentArguments>();
  CLI::App* command = app.add_subcommand(
      "indent", "Nonlinear FE indentation of a layered tissue block by rigid needles, up to puncture (§3.4-3.5)");
  command->add_option("CASE", arguments->case_path, "indentation case file (TOML)")->required();
  command->add_option("--out", arguments->out_dir,
                      "directory for the ParaView series (.pvd/.vtu per step), force-depth and solver CSV, JSON, and the 3D view "
                      "NAME_view.html (docs/views.md)")
      ->type_name("DIR");
  command->add_flag("--json", arguments->json, "print the result as one JSON object (units in the key names)");
  command->add_flag("--no-plot", arguments->no_plot,
                    "with [array] and --out: do not write NAME_needle_map.png (needs /usr/bin/python3 with matplotlib)");
  command->add_flag("--newton-log", arguments->newton_log,
                    "print one line per Newton iteration on stderr: the step's target displacement, the surface "
                    "contact's augmentation, the iteration, its residual, the cut-backs so far, the line search's "
                    "step length, the CG iterations and whether the nodes in contact changed");
  command->add_option("--size-at-tip", arguments->size_at_tip, "override [mesh] size_at_tip, e.g. \"60 um\"");
  command->add_option("--size-far", arguments->size_far, "override [mesh] size_far, e.g. \"400 um\"");
  command->add_option("--depth", arguments->depth, "override [loading] depth, e.g. \"50 um\"");
  command->add_option("--steps", arguments->steps, "override [loading] steps")->check(CLI::Range(1, 100000));
  command->add_option("--angle", arguments->angle,
                      "override [loading] angle, the needle's axis from the skin's normal, e.g. \"15 deg\"");
  command->add_option("--azimuth", arguments->azimuth,
                      "override [loading] azimuth, the tilt's direction from +x, e.g. \"90 deg\"");
  command->footer(indentation_case_help());
  command->callback([arguments] { run_indent(*arguments); });
}

}  // namespace needlekit::cli
