// `needlekit insert CASE.toml [--json] [--out DIR]`: the complete insertion force curve of a needle (or an array):
// the FE indentation up to the puncture point (§3.4-3.5), then the post-puncture cutting force (§3.6), written as
// CSV/JSON with the phases and puncture markers and plotted as a PNG (scripts/plot_force_curve.py).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "commands.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/insertion_curve.hpp"
#include "needlekit/io/force_curve_csv.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/insertion_case.hpp"
#include "needlekit/io/insertion_output.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/scale_warnings.hpp"
#include "progress_bar.hpp"
#include "terminal_warnings.hpp"

#ifndef NEEDLEKIT_SCRIPTS_DIR
#define NEEDLEKIT_SCRIPTS_DIR "scripts"
#endif

namespace needlekit::cli {
namespace {

constexpr const char* kInsertHelp = R"(CASE file (TOML): an indentation case (see `needlekit indent --help`: [needle], [[needles]], [tissue],
[mesh], [loading] (the FE's depth limit for finding the puncture), [model], [puncture]) plus
  [post_puncture]  stiffness = "0.2 N/mm2" (K, a pressure), scale = 0.168 (S), final_depth = "1000 um" (required);
                   samples = 200, reference_radius, max_edge_fraction = 0.025, cap_at_cutting_pressure = true,
                   axial_component = false, side_tolerance = "1 deg", alpha_tolerance = "1 deg",
                   occlusion_test = false, measured = "curve.csv" (fit S to a measured post-puncture curve)
  [pre_puncture]   curve = "pre.csv" (depth_<unit>, force_<unit>), punctured = true: use this curve (its last
                   sample is the puncture point) instead of running the FE
Outputs (in --out DIR, default .): NAME_insertion.csv (depth_um, force_N, phase, punctured_needles, marker),
NAME_insertion.json, NAME_insertion.png (needs /usr/bin/python3 with matplotlib; --no-plot to skip).)";

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

// The pre-puncture curve of needle i of an FE run: its own reaction force against its own depth (the FE depth is
// measured from the first needle's contact; needle i touches `offset` later). Every needle of an array is taken to
// puncture at the run's puncture point (the runner reports one).
insertion::PrePunctureCurve needle_pre_curve(const insertion::IndentationResult& result, std::size_t i, double offset) {
  insertion::PrePunctureCurve pre;
  for (const auto& step : result.steps) {
    const double x = step.depth - offset;
    if (x <= 0) continue;
    pre.curve.depth.push_back(x);
    pre.curve.force.push_back(i < step.needle_force.size() ? step.needle_force[i] : step.force);
  }
  if (result.puncture && result.puncture->depth - offset > 0 && !pre.curve.depth.empty()) {
    pre.puncture = *result.puncture;
    pre.puncture->depth = std::min(result.puncture->depth - offset, pre.curve.depth.back());
  }
  if (pre.curve.depth.empty()) {  // never touched within the run: a zero curve to the run's depth
    pre.curve.depth.push_back(result.steps.empty() ? 1e-9 : std::max(result.steps.back().depth, 1e-9));
    pre.curve.force.push_back(0);
  }
  return pre;
}

void run_insert(const InsertArguments& arguments) {
  const std::filesystem::path case_path(arguments.case_path);
  std::ifstream probe(case_path);
  if (!probe) throw IoError(fmt::format("{}: cannot read", case_path.string()));
  std::stringstream buffer;
  buffer << probe.rdbuf();
  const std::filesystem::path base = case_path.has_parent_path() ? case_path.parent_path() : ".";
  const io::InsertionSettings settings = io::parse_insertion_settings(buffer.str(), case_path.string(), base);
  if (settings.needle_mesh)  // open, non-manifold or inverted: say so (the indentation reader would flip it)
    insertion::validate_needle_surface(geometry::read_triangle_mesh(*settings.needle_mesh, 1.0),
                                       settings.needle_mesh->string());
  insertion::IndentationCase indentation_case =
      io::parse_indentation_case_toml(settings.indentation_text, case_path.string(), base);
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
  print_warnings(io::indentation_scale_warnings(indentation_case));
  create_output_directory(arguments.out_dir);  // before the FE run: a directory that cannot be written fails fast

  // The post-puncture load of the needle (checked before the FE runs: a bad mesh fails fast).
  insertion::TriangleClassificationOptions classification = settings.classification;
  if (indentation_case.geometry) classification.bore_radius = 0.5 * indentation_case.geometry->bore_diameter;
  const geometry::SurfaceMesh surface(indentation_case.needle);
  const insertion::PostPunctureLoads loads =
      insertion::post_puncture_loads(indentation_case.needle, classification, settings.post_puncture, &surface);
  std::optional<insertion::PostPunctureFit> fit;
  if (settings.measured) {
    insertion::PostPunctureFitOptions options;
    options.stiffness = settings.stiffness;
    fit = insertion::fit_post_puncture(loads, io::read_force_curve_csv(*settings.measured), options);
  }

  // The pre-puncture part: the FE (or the given curve).
  const std::size_t count = indentation_case.needles.size();
  double lowest = indentation_case.needles.front().tip_height;
  for (const auto& site : indentation_case.needles) lowest = std::min(lowest, site.tip_height);
  std::vector<insertion::NeedleInsertion> needles(count);
  std::optional<insertion::IndentationResult> fe;
  if (settings.pre_puncture) {
    for (std::size_t i = 0; i < count; ++i) needles[i].pre_puncture = *settings.pre_puncture;
  } else {
    ProgressBar progress(fmt::format("insert {}: FE indentation", indentation_case.name));
    insertion::IndentationOptions options;
    options.progress = [&progress](const insertion::IndentationProgress& p) { progress.update(p.fraction); };
    fe = insertion::run_indentation(indentation_case, options);
    progress.finish();
    if (fe->steps.empty()) {  // a numerical failure with nothing to keep: exit 3, no file
      fmt::print(stderr, "needlekit: {}: the FE indentation converged no load step ({}); nothing to insert\n",
                 case_path.string(), fe->reason);
      throw CommandOutcome{ExitCode::NumericalFailure};
    }
    for (std::size_t i = 0; i < count; ++i)
      needles[i].pre_puncture = needle_pre_curve(*fe, i, indentation_case.needles[i].tip_height - lowest);
  }
  for (std::size_t i = 0; i < count; ++i) {
    needles[i].loads = &loads;
    needles[i].stiffness = settings.stiffness;
    needles[i].scale = settings.scale;
    needles[i].contact_offset = indentation_case.needles[i].tip_height - lowest;
  }
  insertion::InsertionCurveOptions curve_options;
  curve_options.final_depth = settings.final_depth;
  curve_options.cutting_samples = settings.cutting_samples;
  const insertion::InsertionCurve curve = insertion::insertion_curve(needles, curve_options);

  // Outputs: CSV and JSON, then the plot; on a plot failure the CSV and JSON are removed again.
  nlohmann::json json = io::insertion_curve_json(curve);
  json["name"] = indentation_case.name;
  json["needles"] = count;
  json["stiffness_N_per_mm2"] = settings.stiffness * 1e-6;
  json["scale"] = settings.scale;
  json["final_depth_um"] = settings.final_depth * 1e6;
  json["pre_puncture_source"] = fe ? "fe" : "csv";
  json["notes"] = io::indentation_scale_warnings(indentation_case);
  if (fe) {
    json["fe"] = {{"status", insertion::to_string(fe->status)}, {"reason", fe->reason}, {"elements", fe->elements},
                  {"nodes", fe->nodes}, {"total_seconds", fe->total_seconds}};
  }
  const bool fe_failed = fe && fe->status == insertion::IndentationStatus::SolverFailed;
  json["complete"] = !fe_failed;  // false: the curve stops where the FE failed (exit code 3)
  const auto& c = loads.classification;
  json["classification"] = {{"alpha", c.alpha.size()},   {"beta", c.beta.size()},
                            {"side", c.side},            {"back", c.back},
                            {"channel", c.channel},      {"occluded", c.occluded},
                            {"alpha_area_um2", c.alpha_area * 1e12}, {"beta_area_um2", c.beta_area * 1e12},
                            {"loaded_subtriangles", loads.triangles.size()},
                            {"reference_radius_um", loads.reference_radius * 1e6}};
  json["fit"] = nullptr;
  if (fit)
    json["fit"] = {{"scale", fit->scale}, {"stiffness_N_per_mm2", fit->stiffness * 1e-6},
                   {"rms_error_N", fit->rms_error}, {"relative_rms", fit->relative_rms}, {"samples", fit->samples}};

  // Outputs: CSV, JSON and the plot appear together or not at all (StagedFiles: temporary names, renamed at the end).
  const std::filesystem::path dir(arguments.out_dir);
  const std::filesystem::path csv_path = dir / (indentation_case.name + "_insertion.csv");
  const std::filesystem::path json_path = dir / (indentation_case.name + "_insertion.json");
  const std::filesystem::path png_path = dir / (indentation_case.name + "_insertion.png");
  std::vector<std::string> files{csv_path.string(), json_path.string()};
  if (!arguments.no_plot) files.push_back(png_path.string());
  json["files"] = files;
  StagedFiles outputs;
  const std::filesystem::path staged_csv = outputs.write(csv_path, io::insertion_curve_csv(curve));
  outputs.write(json_path, json.dump(2) + "\n");
  if (!arguments.no_plot) {
    std::vector<std::string> command{"/usr/bin/python3", plot_script(), staged_csv.string(),
                                     outputs.stage(png_path).string(), "--title",
                                     fmt::format("{}: K = {:.4g} N/mm2, S = {:.4g}", indentation_case.name,
                                                 settings.stiffness * 1e-6, settings.scale)};
    if (settings.measured) {
      command.push_back("--measured");
      command.push_back(settings.measured->string());
    }
    if (run_program(command) != 0) {
      throw IoError(fmt::format("{}: the plot script {} failed (is python3-matplotlib installed? --no-plot skips the "
                                "plot)",
                                png_path.string(), plot_script()));
    }
  }
  outputs.commit();

  if (arguments.json) {
    fmt::print("{}\n", json.dump(2));
    if (fe_failed) throw CommandOutcome{ExitCode::NumericalFailure};  // the curve up to the FE's failure is kept
    return;
  }
  fmt::print("{}: {} needle(s); {} α- and {} β-triangles ({} side, {} back, {} channel, {} occluded)\n",
             indentation_case.name, count, c.alpha.size(), c.beta.size(), c.side, c.back, c.channel, c.occluded);
  if (fe) fmt::print("FE indentation: {}: {}\n", insertion::to_string(fe->status), fe->reason);
  for (const auto& event : curve.punctures)
    fmt::print("needle {} punctures at {:.4g} um: force {:.5g} N before, {:.5g} N after (relaxation drop {:.5g} N)\n",
               event.needle + 1, event.displacement * 1e6, event.force_before, event.force_after, event.drop);
  if (curve.punctures.empty()) fmt::print("no puncture\n");
  fmt::print("end: {:.4g} um, {:.5g} N ({}: {})\n", curve.depth.back() * 1e6, curve.force.back(),
             insertion::to_string(curve.status), curve.reason);
  if (fit)
    fmt::print("fit to {}: S = {:.5g} at K = {:.4g} N/mm2 (rms {:.3g} N, {:.1f} % of the measured rms)\n",
               settings.measured->string(), fit->scale, fit->stiffness * 1e-6, fit->rms_error,
               100 * fit->relative_rms);
  fmt::print("wrote {}\n", fmt::join(files, ", "));
  if (fe_failed) throw CommandOutcome{ExitCode::NumericalFailure};
}

}  // namespace

void add_insert_command(CLI::App& app) {
  auto arguments = std::make_shared<InsertArguments>();
  CLI::App* command = app.add_subcommand(
      "insert", "Complete insertion force curve: FE indentation to puncture, then the post-puncture cutting force "
                "(§3.4-3.6)");
  command->add_option("CASE", arguments->case_path, "insertion case file (TOML)")->required();
  command->add_option("--out", arguments->out_dir, "directory for the CSV, JSON and PNG (default .)")
      ->type_name("DIR");
  command->add_flag("--json", arguments->json, "print the result as one JSON object (units in the key names)");
  command->add_flag("--no-plot", arguments->no_plot, "do not write the PNG plot");
  command->add_option("--size-at-tip", arguments->size_at_tip, "override [mesh] size_at_tip, e.g. \"60 um\"");
  command->add_option("--size-far", arguments->size_far, "override [mesh] size_far, e.g. \"400 um\"");
  command->add_option("--steps", arguments->steps, "override [loading] steps")->check(CLI::Range(1, 100000));
  command->footer(kInsertHelp);
  command->callback([arguments] { run_insert(*arguments); });
}

}  // namespace needlekit::cli
