#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>

#include "child_process.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/patch_uncertainty_config.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "uncertainty_commands.hpp"

namespace needlekit::cli {
namespace {

std::string plot_script() {
  if (const char* path = std::getenv("NEEDLEKIT_PLOT_SCRIPT")) return path;
  return std::string(NEEDLEKIT_SCRIPTS_DIR) + "/plot_patch_probability.py";
}

void print_table(const nlohmann::json& json) {
  print_study_header(json, "patch fits");
  const auto& nominal = json["nominal"];
  fmt::print("\n  nominal fit: {}, {:.4g} of {} needles succeed\n", nominal["fit_status"].get<std::string>(),
             nominal["success_fraction"].get<double>(), nominal["needles"].get<int>());
  print_probabilities(json, "patch event");
  const auto& f = json["success_fraction"];
  fmt::print("  success fraction: mean {}, q05 {}, q50 {}, q95 {}\n", json_number(f["mean"], "{:.4f}"),
             json_number(f["q05"], "{:.4f}"), json_number(f["q50"], "{:.4f}"), json_number(f["q95"], "{:.4f}"));
  fmt::print("\n  P(success) per needle (rows j, columns i):\n");
  int row = -1;
  for (const auto& needle : json["needles"]) {
    if (needle["j"].get<int>() != row) {
      if (row >= 0) fmt::print("\n");
      row = needle["j"].get<int>();
      fmt::print("  ");
    }
    fmt::print(" {:>6}", json_number(needle["probabilities"]["success"]["value"], "{:.3f}"));
  }
  fmt::print("\n");
  for (const auto& note : json["notes"]) fmt::print("note: {}\n", note.get<std::string>());
}

}  // namespace

std::string patch_inputs_help() {
  std::string help = "Uncertain inputs of a patch case (key, unit, meaning):\n";
  for (const auto& i : uncertainty::patch_inputs()) {
    if (i.placement) help += fmt::format("  {:<34}{:<5}{}\n", i.key, i.unit, i.meaning);
  }
  help += "  and the design inputs above but array.width and insertion.angle\n";
  return help;
}

void run_patch_uncertainty(const UncertaintyArguments& arguments) {
  io::PatchUncertaintyFile file = io::read_patch_uncertainty_file(arguments.path);
  file.sampling.threads = arguments.threads;
  const geometry::BodySurface body = geometry::read_body_surface(file.patch.mesh, file.patch.mesh_unit);
  uncertainty::PatchCase patch_case{&body.surface, file.patch.design, io::fit_and_evaluate_options(file.patch)};
  uncertainty::PatchUncertaintyOptions options;
  options.sampling = file.sampling;
  uncertainty::PatchUncertaintyResult result =
      uncertainty::patch_uncertainty(patch_case, file.inputs, file.correlations, options);
  if (body.flipped) result.notes.insert(result.notes.begin(), body.note);
  const nlohmann::json json = io::patch_uncertainty_json(file, result);
  if (!arguments.out_dir.empty()) {  // every file or none
    const std::filesystem::path dir(arguments.out_dir);
    create_output_directory(dir);
    StagedFiles outputs;
    const std::filesystem::path csv = outputs.write(dir / "needle_probabilities.csv", io::patch_probability_csv(result));
    outputs.write(dir / "needle_probabilities.vtu",
                  io::vtu_document(io::patch_probability_grid(result), dir / "needle_probabilities.vtu"));
    outputs.write(dir / "uncertainty.json", io::json_text(json));
    if (!arguments.no_plot) {
      const std::filesystem::path png = dir / "needle_probabilities.png";
      const std::vector<std::string> command{
          "/usr/bin/python3", plot_script(), csv.string(), outputs.stage(png).string(), "--title",
          fmt::format("{}\nP(success) per needle, {} samples", std::filesystem::path(arguments.path).filename().string(),
                      result.propagation.samples)};
      if (run_program(command) != 0) {
        throw IoError(fmt::format("{}: the plot script {} failed (is python3-matplotlib installed? --no-plot skips the "
                                  "plot)",
                                  png.string(), plot_script()));
      }
    }
    outputs.commit();
  }
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_table(json);
  }
}

}  // namespace needlekit::cli
