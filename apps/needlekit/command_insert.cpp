// `needlekit insert CASE.toml [--json] [--out DIR]`: the complete insertion force curve of a needle (or an array):
// the FE indentation up to the puncture point (§3.4-3.5), then the post-puncture cutting force (§3.6), written as
// CSV/JSON with the phases and puncture markers and plotted as a PNG (scripts/plot_force_curve.py).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/insertion/complete_insertion.hpp"
#include "needlekit/io/complete_insertion_output.hpp"
#include "needlekit/io/indentation_output.hpp"
#include "needlekit/io/insertion_case.hpp"
#include "needlekit/io/insertion_output.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/scale_warnings.hpp"
#include "progress_bar.hpp"
#include "terminal_warnings.hpp"
#include "viewer_sources.hpp"

#ifndef NEEDLEKIT_SCRIPTS_DIR
#define NEEDLEKIT_SCRIPTS_DIR "scripts"
#endif

namespace needlekit::cli {
namespace {

// [post_puncture]'s rows, from the parameter tables of the fit, the curve, the beta load and the classification
// (post_puncture_help), then the measured curve.
constexpr const char* kInsertHelp = R"(CASE file (TOML): an indentation case (see `needlekit indent --help`: [needle], [[needles]], [tissue],
[mesh], [loading] (the FE's depth limit for finding the puncture), [model], [puncture]) plus
{}                   measured = "curve.csv" (fit S to a measured post-puncture curve)
  [pre_puncture]   curve = "pre.csv" (depth_<unit>, force_<unit>), punctured = true: use this curve (its last
                   sample is the puncture point) instead of running the FE
Outputs (in --out DIR, default .): NAME_insertion.csv (depth_um, force_N, phase, punctured_needles, marker),
NAME_insertion.json, NAME_insertion.png (needs /usr/bin/python3 with matplotlib; --no-plot to skip). With
measured, the curve, JSON and plot use the fitted S (JSON: scale, scale_source = "fitted", case_scale). A FE run
that stops converging writes what converged (the JSON alone if no step did) and exits with code 3.)";

std::string post_puncture_help() {
  std::vector<ParameterText> texts;
  const insertion::CompleteInsertionOptions defaults;
  io::for_each_post_puncture_table(defaults, [&texts](const auto& table, const auto& options) {
    const std::vector<ParameterText> rows = parameter_texts(table, options);
    texts.insert(texts.end(), rows.begin(), rows.end());
  });
  return settings_help(texts, "post_puncture", "  [post_puncture]");
}

struct InsertArguments {
  std::string case_path;
  std::string out_dir = ".";
  bool json = false;
  bool no_plot = false;
  std::string size_at_tip;
  std::string size_far;
  int steps = 0;
};

std::string plot_script() {
  if (const char* path = std::getenv("NEEDLEKIT_PLOT_SCRIPT")) return path;
  return std::string(NEEDLEKIT_SCRIPTS_DIR) + "/plot_force_curve.py";
}

// The case file with the command line's overrides of the mesh and the steps.
io::InsertionCase read_case(const InsertArguments& arguments) {
  io::InsertionCase c = io::read_insertion_case(arguments.case_path);
  insertion::IndentationCase& indentation_case = c.indentation;
  if (!arguments.size_at_tip.empty()) {
    indentation_case.block.size_at_site =
        units::parse_quantity(arguments.size_at_tip, units::Dimension::Length, "--size-at-tip");
    indentation_case.block.size_far = std::max(indentation_case.block.size_far, indentation_case.block.size_at_site);
  }
  if (!arguments.size_far.empty())
    indentation_case.block.size_far = units::parse_quantity(arguments.size_far, units::Dimension::Length, "--size-far");
  if (arguments.steps > 0) indentation_case.steps = arguments.steps;
  indentation_case.stop_at_puncture = true;
  insertion::validate(indentation_case);
  return c;
}

// The outputs: the JSON always; the CSV and the plot when the curve has samples (the FE converged at least one step);
// the 3D view when the FE ran. All are staged and renamed together: on a plot failure or an interrupt none is
// written. Adds "files" and "view" to `json`; returns the view page's path, or empty without a view.
std::filesystem::path write_outputs(const InsertArguments& arguments, const io::InsertionCase& c,
                                    const insertion::CompleteInsertionResult& result,
                                    const std::optional<io::IndentationView>& view, const io::ViewerFiles& viewer,
                                    nlohmann::json& json) {
  const std::string& name = c.indentation.name;
  const insertion::InsertionCurve& curve = result.curve;
  const std::filesystem::path dir(arguments.out_dir);
  const std::filesystem::path csv_path = dir / (name + "_insertion.csv");
  const std::filesystem::path json_path = dir / (name + "_insertion.json");
  const std::filesystem::path png_path = dir / (name + "_insertion.png");
  const bool has_curve = !curve.depth.empty();
  std::vector<std::string> files;
  if (has_curve) files.push_back(csv_path.string());
  files.push_back(json_path.string());
  if (has_curve && !arguments.no_plot) files.push_back(png_path.string());
  const bool has_view = view && view->steps() > 0;
  const std::string view_script = name + "_view.js";
  const std::filesystem::path view_page = dir / (name + "_view.html");
  json["files"] = files;
  json["view"] = has_view ? nlohmann::json(view_page.string()) : nlohmann::json(nullptr);  // docs/views.md
  StagedFiles outputs;
  std::filesystem::path staged_csv;
  if (has_curve) staged_csv = outputs.write(csv_path, io::insertion_curve_csv(curve));
  outputs.write(json_path, io::json_text(json));
  if (has_view) {
    outputs.write(dir / view_script, io::view_script(view->json()));
    io::stage_view_page(outputs, dir, name + "_view.html", name + ": 3D view", {view_script}, viewer);
  }
  if (has_curve && !arguments.no_plot) {
    const std::string s = result.fit
                              ? fmt::format("S = {:.4g} (fitted; case {:.4g})", result.scale, c.options.model.scale)
                              : fmt::format("S = {:.4g}", result.scale);
    std::vector<std::string> command{"/usr/bin/python3", plot_script(), staged_csv.string(),
                                     outputs.stage(png_path).string(), "--title",
                                     fmt::format("{}: K = {:.4g} N/mm2, {}", name, result.stiffness * 1e-6, s)};
    if (c.measured) {
      command.push_back("--measured");
      command.push_back(c.measured->string());
    }
    if (run_program(command) != 0) {
      throw IoError(fmt::format("{}: the plot script {} failed (is python3-matplotlib installed? --no-plot skips the "
                                "plot)",
                                png_path.string(), plot_script()));
    }
  }
  outputs.commit();
  return has_view ? view_page : std::filesystem::path();
}

void print_summary(const io::InsertionCase& c, const insertion::CompleteInsertionResult& result,
                   const nlohmann::json& json, const std::filesystem::path& view_page) {
  const insertion::IndentationCase& indentation_case = c.indentation;
  const insertion::InsertionCurve& curve = result.curve;
  const auto& classes = result.loads.classification;
  fmt::print("{}: {} needle(s); {} α- and {} β-triangles ({} side, {} back, {} channel, {} occluded)\n",
             indentation_case.name, indentation_case.needles.size(), classes.alpha.size(), classes.beta.size(),
             classes.side, classes.back, classes.channel, classes.occluded);
  if (const auto& fe = result.indentation)
    fmt::print("FE indentation ({}): {}: {}\n", io::fe_models_text(indentation_case), insertion::to_string(fe->status),
               fe->reason);
  for (const auto& event : curve.punctures)
    fmt::print("needle {} punctures at {:.4g} um: force {:.5g} N before, {:.5g} N after (relaxation drop {:.5g} N)\n",
               event.needle + 1, event.displacement * 1e6, event.force_before, event.force_after, event.drop);
  if (curve.punctures.empty()) fmt::print("no puncture\n");
  if (!curve.depth.empty()) fmt::print("end: {:.4g} um, {:.5g} N\n", curve.depth.back() * 1e6, curve.force.back());
  fmt::print("{}: {}\n", insertion::to_string(result.status), result.reason);
  if (const auto& fit = result.fit)
    fmt::print("fit to {}: S = {:.5g} at K = {:.4g} N/mm2 (rms {:.3g} N, {:.1f} % of the measured rms); the curve "
               "uses the fitted S (the case's S = {:.4g})\n",
               c.measured->string(), fit->scale, fit->stiffness * 1e-6, fit->rms_error, 100 * fit->relative_rms,
               c.options.model.scale);
  fmt::print("wrote {}\n", fmt::join(json["files"].get<std::vector<std::string>>(), ", "));
  if (!view_page.empty()) fmt::print("3D view: {} (open it in a browser)\n", view_page.string());
}

void run_insert(const InsertArguments& arguments) {
  io::InsertionCase c = read_case(arguments);
  insertion::IndentationCase& indentation_case = c.indentation;
  const std::vector<std::string> notes = io::indentation_scale_warnings(indentation_case);
  print_warnings(notes);
  create_output_directory(arguments.out_dir);  // before the FE run: a directory that cannot be written fails fast

  std::optional<ProgressBar> progress;
  if (!c.options.pre_puncture) progress.emplace(fmt::format("insert {}: FE indentation", indentation_case.name));
  c.options.indentation.progress = [&progress](const insertion::IndentationProgress& p) { progress->update(p.fraction); };
  // The 3D view of the FE part (docs/views.md).
  std::optional<io::IndentationView> view;
  io::ViewerFiles viewer;
  if (!c.options.pre_puncture) {
    viewer = io::viewer_files(viewer_sources());  // before the FE run: a missing file fails fast
    view.emplace(indentation_case);
    c.options.indentation.on_mesh = [&view](const mesh::TetMesh& tissue) { view->set_mesh(tissue); };
    c.options.indentation.on_step = [&view](const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
      view->add_step(step, solver);
    };
  }
  const insertion::CompleteInsertionResult result = insertion::complete_insertion(indentation_case, c.options);
  if (progress) progress->finish();

  nlohmann::json json = io::complete_insertion_json(c, result, notes);
  const std::filesystem::path view_page = write_outputs(arguments, c, result, view, viewer, json);
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_summary(c, result, json, view_page);
  }
  if (result.status == insertion::CompleteInsertionStatus::SolverFailed) throw CommandOutcome{ExitCode::NumericalFailure};
}

}  // namespace

void add_insert_command(CLI::App& app) {
  auto arguments = std::make_shared<InsertArguments>();
  CLI::App* command = app.add_subcommand(
      "insert", "Complete insertion force curve: FE indentation to puncture, then the post-puncture cutting force "
                "(§3.4-3.6)");
  command->add_option("CASE", arguments->case_path, "insertion case file (TOML)")->required();
  command->add_option("--out", arguments->out_dir,
                      "directory for the CSV, JSON, PNG and the 3D view NAME_view.html (default .)")
      ->type_name("DIR");
  command->add_flag("--json", arguments->json, "print the result as one JSON object (units in the key names)");
  command->add_flag("--no-plot", arguments->no_plot, "do not write the PNG plot");
  command->add_option("--size-at-tip", arguments->size_at_tip, "override [mesh] size_at_tip, e.g. \"60 um\"");
  command->add_option("--size-far", arguments->size_far, "override [mesh] size_far, e.g. \"400 um\"");
  command->add_option("--steps", arguments->steps, "override [loading] steps")->check(CLI::Range(1, 100000));
  command->footer(fmt::format(kInsertHelp, post_puncture_help()));
  command->callback([arguments] { run_insert(*arguments); });
}

}  // namespace needlekit::cli
