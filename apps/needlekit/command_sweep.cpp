// `needlekit sweep DESIGN.toml --vary PARAM=FROM:TO:STEP`: the performance index as one parameter varies, the
// others fixed (dissertation §6.3.1, Figs 6.18 and 6.19).
#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/analysis/sensitivity_sweep.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/scale_warnings.hpp"
#include "terminal_warnings.hpp"

namespace needlekit::cli {
namespace {

struct SweepArguments {
  std::string design_path;
  std::string vary;
  std::string csv_path;
  bool json = false;
};

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find(separator, start)) != std::string_view::npos; start = end + 1) {
    parts.push_back(text.substr(start, end - start));
  }
  parts.push_back(text.substr(start));
  return parts;
}

// "base_diameter=50um:300um:10um" -> SI sweep options.
analysis::SweepOptions parse_vary(std::string_view text) {
  const std::size_t equals = text.find('=');
  const std::vector<std::string_view> bounds =
      equals == std::string_view::npos ? std::vector<std::string_view>{} : split(text.substr(equals + 1), ':');
  if (bounds.size() != 3) {
    throw InvalidInput(fmt::format("--vary: '{}' is not PARAMETER=FROM:TO:STEP, expected e.g. "
                                   "base_diameter=50um:300um:10um",
                                   text));
  }
  analysis::SweepOptions sweep;
  sweep.parameter = analysis::sweep_parameter_from_string(text.substr(0, equals), "--vary");
  const units::Dimension dimension = analysis::sweep_parameter_dimension(sweep.parameter);
  const std::string_view name = analysis::to_string(sweep.parameter);
  sweep.from = units::parse_quantity(bounds[0], dimension, fmt::format("--vary {} (from)", name));
  sweep.to = units::parse_quantity(bounds[1], dimension, fmt::format("--vary {} (to)", name));
  sweep.step = units::parse_quantity(bounds[2], dimension, fmt::format("--vary {} (step)", name));
  return sweep;
}

void run_sweep(const SweepArguments& arguments) {
  const analysis::SweepOptions sweep = parse_vary(arguments.vary);
  const io::DesignFile file = io::read_design_file(arguments.design_path);
  print_warnings(io::needle_scale_warnings(file.design.needle));
  const analysis::SweepResult result = analysis::sensitivity_sweep(file.design, file.conditions, file.options, sweep);
  const std::string csv = io::sweep_csv(result);
  if (!arguments.csv_path.empty()) io::write_text_file_atomically(arguments.csv_path, csv);
  if (arguments.json) {
    fmt::print("{}", io::json_text(io::sweep_json(result)));
  } else if (arguments.csv_path.empty()) {
    fmt::print("{}", csv);
  }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto arguments = std::make_shared<SweepArguments>();
  CLI::App* command = app.add_subcommand(
      "sweep", "Performance index as one parameter varies, the others fixed (dissertation Figs 6.18, 6.19)");
  command->add_option("DESIGN", arguments->design_path, "design file (TOML), format below")->required();
  command
      ->add_option("--vary", arguments->vary,
                   fmt::format("the parameter and its inclusive range, step > 0, with units (e.g. "
                               "base_diameter=50um:300um:10um, angle=0deg:60deg:5deg, needles_per_row=5:25:1); "
                               "PARAM = {}. A cylinder's tip and base vary together. Points whose design is invalid "
                               "are reported as constraint_violated",
                               choices_of(analysis::kSweepParameterNames)))
      ->type_name("PARAM=FROM:TO:STEP")
      ->required();
  command->add_option("--csv", arguments->csv_path,
                      "write the CSV (value, performance_index_per_um, status, deformation_um, cutting_depth_um, "
                      "Q_um2, puncture_force_N, critical_buckling_load_N, buckling_force_N, reason) to FILE instead "
                      "of stdout")
      ->type_name("FILE");
  command->add_flag("--json", arguments->json, "print every point as JSON on stdout (with all quantities)");
  command->footer(design_file_help());
  command->callback([arguments] { run_sweep(*arguments); });
}

}  // namespace needlekit::cli
