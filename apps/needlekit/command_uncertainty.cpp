// `needlekit uncertainty UQ.toml`: the probability that a design works when its inputs are uncertain (sampling with
// Sobol' indices). Parses, calls uncertainty::design_uncertainty(), presents. A patch case (a file with [surface])
// goes to run_patch_uncertainty() (command_uncertainty_patch.cpp).
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/uncertainty_config.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "uncertainty_commands.hpp"

namespace needlekit::cli {
namespace {

void print_table(const nlohmann::json& json) {
  print_study_header(json, "evaluations");
  print_probabilities(json, "event");
  const auto& index = json["performance_index_per_um"];
  fmt::print("\n  performance index (1/um): mean {} (nominal {}), sd {}, q05 {}, q50 {}, q95 {}\n",
             json_number(index["mean"]), json_number(json["nominal"]["performance_index_per_um"]),
             json_number(index["sd"]), json_number(index["q05"]), json_number(index["q50"]), json_number(index["q95"]));
  if (!json["sobol"].is_null()) {
    fmt::print("\n  {:<34}{:>10}{:>10}{:>14}{:>14}   (performance index)\n", "input", "S_i", "ST_i", "success S_i",
               "success ST_i");
    const auto& sobol = json["sobol"];
    const auto& success = sobol["events"]["success"];
    for (const auto& input : json["inputs"]) {
      const std::string key = input["key"].get<std::string>();
      fmt::print("  {:<34}{:>10}{:>10}{:>14}{:>14}\n", key, json_number(sobol["first"][key], "{:.3f}"),
                 json_number(sobol["total"][key], "{:.3f}"), json_number(success["first"][key], "{:.3f}"),
                 json_number(success["total"][key], "{:.3f}"));
    }
  }
  fmt::print("\n  one at a time (Fig 6.18): index at the input's 5 % and 95 % quantiles, others nominal\n");
  for (const auto& [key, o] : json["one_at_a_time"].items()) {
    fmt::print("  {:<34}{:.6g} {} -> {:.4g} 1/um, {:.6g} {} -> {:.4g} 1/um\n", key, o["low"].get<double>(),
               o["unit"].get<std::string>(), o["performance_index_low_per_um"].get<double>(), o["high"].get<double>(),
               o["unit"].get<std::string>(), o["performance_index_high_per_um"].get<double>());
  }
  for (const auto& note : json["notes"]) fmt::print("note: {}\n", note.get<std::string>());
}

void run_uncertainty(const UncertaintyArguments& arguments) {
  io::UncertaintyFile file = io::read_uncertainty_file(arguments.path);
  file.sampling.threads = arguments.threads;
  uncertainty::DesignUncertaintyOptions options;
  options.sampling = file.sampling;
  const uncertainty::DesignUncertaintyResult result =
      uncertainty::design_uncertainty(file.design, file.inputs, file.correlations, options);
  const nlohmann::json json = io::uncertainty_json(file, result);
  if (!arguments.out_dir.empty()) {
    const std::filesystem::path dir(arguments.out_dir);
    std::filesystem::create_directories(dir);
    io::write_text_file_atomically(dir / "performance_index_histogram.csv", io::index_histogram_csv(result));
    io::write_text_file_atomically(dir / "sobol_indices.csv", io::sobol_csv(result));
    io::write_text_file_atomically(dir / "uncertainty.json", io::json_text(json));
  }
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_table(json);
  }
}

// The distributions, methods and inputs from their tables (uncertainty/distribution.hpp, sample_points.hpp,
// design_inputs.hpp).
std::string tables_help() {
  std::string help = "\nDistributions:\n";
  for (const auto& d : uncertainty::kDistributionKindNames) help += fmt::format("  {:<18}{}\n", d.name, d.meaning);
  help += "Sampling methods:\n";
  for (const auto& m : uncertainty::kSamplingMethodNames) help += fmt::format("  {:<18}{}\n", m.name, m.meaning);
  help += "Uncertain inputs (key, unit, meaning):\n";
  for (const auto& i : uncertainty::design_inputs()) {
    help += fmt::format("  {:<34}{:<5}{}\n", i.key, i.unit, i.meaning);
  }
  return help;
}

}  // namespace

std::string json_number(const nlohmann::json& value, std::string_view format) {
  return value.is_null() ? "-" : fmt::format(fmt::runtime(format), value.get<double>());
}

void print_study_header(const nlohmann::json& json, std::string_view runs) {
  fmt::print("{} samples ({}, seed {}), {} {}: {}\n", json["samples"].get<std::size_t>(),
             json["method"].get<std::string>(), json["seed"].get<std::uint64_t>(),
             json["evaluations"].get<std::size_t>(), runs, json["status"].get<std::string>());
  if (!json["reason"].get<std::string>().empty()) fmt::print("{}\n", json["reason"].get<std::string>());
  for (const auto& input : json["inputs"]) {
    fmt::print("  {:<34}{}\n", input["key"].get<std::string>(), input["distribution"].get<std::string>());
  }
}

void print_probabilities(const nlohmann::json& json, std::string_view what) {
  fmt::print("\n  {:<22}{:>10}   {}\n", what, "P", "95 % interval");
  for (const auto& [event, p] : json["probabilities"].items()) {
    fmt::print("  {:<22}{:>10}   [{}, {}]\n", event, json_number(p["value"], "{:.6f}"),
               json_number(p["ci95"][0], "{:.6f}"), json_number(p["ci95"][1], "{:.6f}"));
  }
}

void add_uncertainty_command(CLI::App& app) {
  auto arguments = std::make_shared<UncertaintyArguments>();
  CLI::App* command = app.add_subcommand(
      "uncertainty",
      "Probability that a design punctures, does not buckle or bend, and reaches its target when its inputs are "
      "uncertain; distribution of the performance index; Sobol' indices");
  command->add_option("UQ", arguments->path,
                      "uncertainty file (TOML): a design file or a patch case, plus [uncertain], [sampling]")
      ->required();
  command->add_flag("--json", arguments->json, "print the result as one JSON object (units in the key names)");
  command->add_option("--out", arguments->out_dir,
                      "also write uncertainty.json, performance_index_histogram.csv and sobol_indices.csv to DIR; for a "
                      "patch case uncertainty.json, needle_probabilities.csv, .vtu and .png; for an FE case "
                      "uncertainty.json and fe_runs.csv")
      ->type_name("DIR");
  command->add_flag("--no-plot", arguments->no_plot, "patch case: no PNG (it needs /usr/bin/python3 with matplotlib)");
  command->add_option("--threads", arguments->threads,
                      "worker threads, >= 0 (0: all hardware threads); the result does not depend on it")
      ->type_name("N")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->footer(uncertainty_file_help() + "\n" + tables_help() + patch_inputs_help() + fe_help() + "\n" +
                  design_file_help());
  command->callback([arguments] {
    const io::UncertaintyFileKind kind = io::uncertainty_file_kind(arguments->path);
    if (arguments->no_plot && kind != io::UncertaintyFileKind::Patch) {
      throw InvalidInput(fmt::format("{}: --no-plot applies to patch cases only; a design or FE uncertainty file "
                                     "writes no plot",
                                     arguments->path));
    }
    switch (kind) {
      case io::UncertaintyFileKind::Patch: return run_patch_uncertainty(*arguments);
      case io::UncertaintyFileKind::FeCase: return run_fe_uncertainty(*arguments);
      case io::UncertaintyFileKind::Design: return run_uncertainty(*arguments);
    }
  });
}

}  // namespace needlekit::cli
