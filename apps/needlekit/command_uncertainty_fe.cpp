#include <fmt/format.h>

#include <filesystem>

#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/io/fe_uncertainty_config.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "needlekit/uncertainty/fe_surrogate_parameters.hpp"
#include "progress_bar.hpp"
#include "uncertainty_commands.hpp"

namespace needlekit::cli {
namespace {

void print_table(const nlohmann::json& json) {
  print_study_header(json, "surrogate evaluations");
  const auto& s = json["surrogate"];
  fmt::print("\n  surrogate: {} ({} terms), {} FE runs on one mesh of {} tetrahedra ({} design, {} held out), {:.3g} s\n",
             s["kind"].get<std::string>(), s["terms"].get<int>(), s["fe_runs"].get<int>(), s["elements"].get<int>(),
             s["design_runs"].get<int>(), s["validation_runs"].get<int>(), s["fe_seconds"].get<double>());
  for (const char* output : {"puncture_depth", "puncture_force"}) {
    const auto& v = s["validation_error"][output];
    const auto& f = s["fit_error"][output];
    fmt::print("  {:<16} error on held-out FE runs: max {:.3g} %, rms {:.3g} % (at the design runs: max {:.3g} %)\n",
               output, 100 * v["max_relative"].get<double>(), 100 * v["rms_relative"].get<double>(),
               100 * f["max_relative"].get<double>());
  }
  const auto& nominal = json["nominal"];
  fmt::print("  nominal FE run: {}, puncture at {} um, {} N\n", nominal["status"].get<std::string>(),
             json_number(nominal["puncture_depth_um"]), json_number(nominal["puncture_force_N"]));
  print_probabilities(json, fmt::format("event (X = {:.4g} um)", json["depth_limit_um"].get<double>()));
  for (const auto& [key, unit] : {std::pair{"puncture_depth_um", "um"}, std::pair{"puncture_force_N", "N"}}) {
    const auto& d = json[key];
    if (d.is_null()) continue;
    fmt::print("  {:<18} mean {} {}, sd {}, q05 {}, q50 {}, q95 {}\n", key, json_number(d["mean"]), unit,
               json_number(d["sd"]), json_number(d["q05"]), json_number(d["q50"]), json_number(d["q95"]));
  }
  for (const auto& note : json["notes"]) fmt::print("note: {}\n", note.get<std::string>());
}

}  // namespace

std::string fe_help() {
  return fmt::format(
      "FE case (the FE surrogate): a UQ file with case = \"indent_....toml\" (an indentation case, relative to the UQ "
      "file) instead of a design, [uncertain] keys {}, [sampling], and optional\n{}",
      uncertainty::kFeInputKeys,
      settings_help(parameter_texts<uncertainty::FeSurrogateOptions>(uncertainty::kFeSurrogateParameters),
                    "surrogate", "  [surrogate]"));
}

void run_fe_uncertainty(const UncertaintyArguments& arguments) {
  io::FeUncertaintyFile file = io::read_fe_uncertainty_file(arguments.path);
  file.options.sampling.threads = arguments.threads;
  ProgressBar bar("FE runs");
  file.options.progress = [&bar](int done, int total) { bar.update(static_cast<double>(done) / total); };
  const uncertainty::FeSurrogateResult result =
      uncertainty::fe_surrogate(file.indentation, file.inputs, file.correlations, file.options);
  bar.finish();
  const nlohmann::json json = io::fe_uncertainty_json(file, result);
  if (!arguments.out_dir.empty()) {
    const std::filesystem::path dir(arguments.out_dir);
    create_output_directory(dir);
    StagedFiles outputs;
    outputs.write(dir / "uncertainty.json", io::json_text(json));
    outputs.write(dir / "fe_runs.csv", io::fe_runs_csv(file, result));
    outputs.commit();
  }
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_table(json);
  }
  if (result.status == uncertainty::FeSurrogateStatus::Failed) throw CommandOutcome{ExitCode::NumericalFailure};
}

}  // namespace needlekit::cli
