// `needlekit calibrate CALIBRATION.toml [--json] [--out DIR] [--write-case FILE]`: fit case-file parameters (tissue
// moduli, puncture criteria, K*S, the analytic model's alpha/tau and puncture-force law) to measured force curves
// and puncture points (calibration/calibrate.hpp), and present the result: values with 95 % intervals, correlations,
// identifiability warnings, residuals per experiment, a measured-vs-fitted plot (scripts/plot_calibration.py).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/calibration/calibrate.hpp"
#include "needlekit/calibration/calibration_output.hpp"
#include "needlekit/calibration/calibration_solver_parameters.hpp"
#include "needlekit/calibration/case_parameters.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/result_writers.hpp"

#ifndef NEEDLEKIT_SCRIPTS_DIR
#define NEEDLEKIT_SCRIPTS_DIR "scripts"
#endif

namespace needlekit::cli {
namespace {

struct CalibrateArguments {
  std::string file;
  std::string out_dir = ".";
  std::string write_case;
  bool json = false;
  bool no_plot = false;
};

std::string help_text() {
  std::string kinds;
  for (const calibration::ParameterKind& kind : calibration::parameter_kinds())
    kinds += fmt::format("  {:<34}{}\n", kind.pattern, kind.meaning);
  return fmt::format(R"(CALIBRATION file (TOML):
  name = "phantom"                                   optional, names the outputs
{}  [[parameters]]
  path = "tissue.layers.0.youngs_modulus"           a key of the experiments' case files (below)
  initial = "0.1 MPa"                                with a unit (a number for dimensionless keys)
  bounds = ["0.01 MPa", "10 MPa"]
  [[experiments]]
  name = "sharp"
  case = "insert_sharp_bevel.toml"                   an indent or insert case, or a design file (analytic model)
  measured = "sharp_curve.csv"                       depth_<unit>, force_<unit>, >= 3 samples; and/or
  puncture = {{ depth = "230 um", force = "0.014 N" }} (design files: deformation d and F(A))
  weights = {{ curve = 1, puncture = 1 }}
Calibratable keys (N: a layer or table index):
{}Outputs (--out DIR): NAME_calibration.json, NAME_calibration_curves.csv, NAME_calibration.png (--no-plot skips it).
Exit code 3 when the fit does not converge (results written), 2 on bad input (nothing written).)",
                     settings_help(parameter_texts<calibration::SolverSettings>(calibration::kCalibrationSolverParameters),
                                   "solver", "  [solver]"),
                     kinds);
}

std::string plot_script() {
  if (const char* path = std::getenv("NEEDLEKIT_CALIBRATION_PLOT_SCRIPT")) return path;
  return std::string(NEEDLEKIT_SCRIPTS_DIR) + "/plot_calibration.py";
}

std::string interval_text(const calibration::FittedParameter& p) {
  if (!p.ci95) return "not identifiable";
  return fmt::format("[{}, {}] (+-{:.3g} %{})", calibration::as_given(p.spec, p.ci95->first),
                     calibration::as_given(p.spec, p.ci95->second),
                     100 * (p.ci95->second - p.value) / std::abs(p.value),
                     p.discretisation_error > 0
                         ? fmt::format(", of which mesh {:.3g} %", 100 * p.discretisation_error / std::abs(p.value))
                         : "");
}

void print_result(const calibration::CalibrationProblem& problem, const calibration::CalibrationResult& r) {
  fmt::print("{}: {} after {} iterations ({}), rms relative residual {:.4g}, {} FE runs, {:.1f} s\n", problem.name,
             calibration::to_string(r.status), r.iterations, r.reason, r.rms_relative, r.model_runs, r.seconds);
  fmt::print("{:<36} {:>16} {:>16}  {}\n", "parameter", "initial", "fitted", "95 % interval");
  for (const calibration::FittedParameter& p : r.parameters)
    fmt::print("{:<36} {:>16} {:>16}  {}{}\n", p.spec.path, calibration::as_given(p.spec, p.spec.initial),
               calibration::as_given(p.spec, p.value), interval_text(p), p.at_bound ? "  (at a bound)" : "");
  if (r.parameters.size() > 1) {
    fmt::print("correlation:\n");
    for (Eigen::Index i = 0; i < r.correlation.rows(); ++i) {
      std::vector<std::string> row;
      for (Eigen::Index j = 0; j < r.correlation.cols(); ++j)
        row.push_back(std::isfinite(r.correlation(i, j)) ? fmt::format("{:7.3f}", r.correlation(i, j)) : "      -");
      fmt::print("  {:<34} {}\n", r.parameters[i].spec.path, fmt::join(row, " "));
    }
  }
  for (std::size_t e = 0; e < r.experiments.size(); ++e) {
    const calibration::ExperimentFit& fit = r.experiments[e];
    const auto& p = fit.prediction.puncture;
    fmt::print("experiment {} ({}): rms relative {:.4g}; model puncture {}; {}\n", fit.name,
               calibration::to_string(fit.kind), fit.rms_relative,
               p ? fmt::format("{:.4g} um, {:.5g} N", p->depth * 1e6, p->force) : "none", fit.prediction.status);
  }
  for (const std::string& warning : r.warnings) fmt::print("warning: {}\n", warning);
}

void run_calibrate(const CalibrateArguments& arguments) {
  const calibration::CalibrationProblem problem = calibration::read_calibration_file(arguments.file);
  calibration::CalibrationOptions options;
  options.progress = [&](const calibration::CalibrationProgress& p) {
    std::vector<std::string> values;
    for (std::size_t j = 0; j < p.values.size(); ++j)
      values.push_back(fmt::format("{} = {}", problem.parameters[j].path, calibration::as_given(problem.parameters[j], p.values[j])));
    fmt::print(stderr, "calibrate {}: iteration {}: rms {:.4g}; {} ({} FE runs, {:.1f} s)\n", problem.name,
               p.iteration, p.rms_relative, fmt::join(values, ", "), p.model_runs, p.seconds);
    return !interrupt_requested();
  };
  options.stop_requested = [] { return interrupt_requested(); };  // Ctrl-C inside an FE run, not after it
  const calibration::CalibrationResult result = calibration::calibrate(problem, options);
  if (result.status == calibration::CalibrationStatus::Stopped) throw Interrupted();  // nothing written

  nlohmann::json json = calibration::calibration_json(problem, result);
  const std::filesystem::path dir(arguments.out_dir);
  create_output_directory(dir);
  const std::filesystem::path json_path = dir / (problem.name + "_calibration.json");
  const std::filesystem::path csv_path = dir / (problem.name + "_calibration_curves.csv");
  const std::filesystem::path png_path = dir / (problem.name + "_calibration.png");
  std::vector<std::string> files{json_path.string(), csv_path.string()};
  if (!arguments.no_plot) files.push_back(png_path.string());
  if (!arguments.write_case.empty()) files.push_back(arguments.write_case);
  json["files"] = files;
  StagedFiles outputs;  // all or none: a failed plot or an interrupt leaves no partial set
  const std::filesystem::path staged_csv = outputs.write(csv_path, calibration::calibration_curves_csv(problem, result));
  outputs.write(json_path, io::json_text(json));
  if (!arguments.write_case.empty())
    outputs.write(arguments.write_case, calibration::calibrated_case_text(problem, 0, result.values()));
  if (!arguments.no_plot) {
    const std::vector<std::string> command{"/usr/bin/python3", plot_script(), staged_csv.string(),
                                           outputs.stage(png_path).string(), "--title",
                                           fmt::format("{}: measured vs fitted", problem.name)};
    if (run_program(command) != 0) {
      throw IoError(fmt::format("{}: the plot script {} failed (is python3-matplotlib installed? --no-plot skips "
                                "the plot)",
                                png_path.string(), plot_script()));
    }
  }
  outputs.commit();
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_result(problem, result);
    fmt::print("wrote {}\n", fmt::join(files, ", "));
  }
  if (result.status != calibration::CalibrationStatus::Converged) throw CommandOutcome{ExitCode::NumericalFailure};
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto arguments = std::make_shared<CalibrateArguments>();
  CLI::App* command = app.add_subcommand(
      "calibrate", "Fit tissue and puncture parameters of case files to measured force curves and puncture points");
  command->add_option("CALIBRATION", arguments->file, "calibration file (TOML), format below")->required();
  command->add_option("--out", arguments->out_dir, "directory for the JSON, CSV and PNG (default .)")->type_name("DIR");
  command->add_option("--write-case", arguments->write_case,
                      "write the first experiment's case file with the fitted values to FILE")
      ->type_name("FILE");
  command->add_flag("--json", arguments->json, "print the result as one JSON object (SI values, units named)");
  command->add_flag("--no-plot", arguments->no_plot, "do not write the PNG plot");
  command->footer(help_text());
  command->callback([arguments] { run_calibrate(*arguments); });
}

}  // namespace needlekit::cli
