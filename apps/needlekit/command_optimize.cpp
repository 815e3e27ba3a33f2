// `needlekit optimize SPACE.toml`: the best array of one needle type over a grid (dissertation §4.8, Fig 6.20).
#include <fmt/format.h>

#include <memory>
#include <string>

#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/robust_design_run.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "progress_bar.hpp"

namespace needlekit::cli {
namespace {

struct OptimizeArguments {
  std::string space_path;
  bool json = false;
  int top = 10;
  bool published_compat = false;
  bool certified = false;
  int threads = 0;
  std::string out_path;
  std::uint64_t max_grid_points = limits::kMaxBruteForcePoints;
  double max_memory_gib = limits::kMaxOptimizerMemoryBytes / (1ULL << 30);
};

void print_table(const analysis::DesignSpace& space, const analysis::OptimizerResult& result) {
  fmt::print("{} {} needles, {}: {}\n", space.hollow ? "hollow" : "solid", needle::to_string(space.shape),
             space.material.name, analysis::to_string(result.status));
  if (!result.reason.empty()) fmt::print("{}\n", result.reason);
  if (!result.top.empty()) {
    fmt::print("{:>4} {:>4} {:>8} {:>8} {:>8} {:>9} {:>8} {:>13}\n", "rank", "n", "D1 um", "D2 um", "D3 um", "w um",
               "L um", "PI 1/um");
    int rank = 1;
    for (const analysis::DesignCandidate& c : result.top) {
      fmt::print("{:>4} {:>4} {:>8.6g} {:>8.6g} {:>8} {:>9.6g} {:>8.6g} {:>13.6e}\n", rank++, c.needles_per_row,
                 c.tip_diameter * 1e6, c.base_diameter * 1e6,
                 c.bore_diameter > 0 ? fmt::format("{:.6g}", c.bore_diameter * 1e6) : "-", c.width * 1e6,
                 c.length * 1e6, c.performance_index * 1e-6);
    }
  }
  const analysis::PunctureForceLawKind law = space.conditions.tissue.force_law.kind;
  fmt::print("models: puncture force law {} ({}){}\n", analysis::to_string(law),
             analysis::puncture_force_law_source(law),
             result.top.empty() ? ""
                                : fmt::format("; buckling {} ({}, K = {:g})",
                                              analysis::to_string(result.top.front().details.buckling.end_condition),
                                              analysis::to_string(result.top.front().details.buckling.method),
                                              result.top.front().details.buckling.effective_length_factor));
  if (result.top_outside_force_law_range > 0) {
    fmt::print("warning: {} of the {} best designs lie outside the validity range of the puncture force law {}: "
               "their force is an extrapolation (see each design's notes)\n",
               result.top_outside_force_law_range, result.top.size(), analysis::to_string(law));
  }
  fmt::print("grid points {}, evaluated {}, feasible {}{}, {:.3f} s\n", result.grid_points, result.evaluated,
             result.feasible, result.feasible == 0 && !result.top.empty() ? " (not counted by --certified)" : "",
             result.seconds);
}

void print_robust(const nlohmann::json& robust) {
  fmt::print("robust design, P(success) >= {:g} ({} samples, {}): {}\n", robust["min_success_probability"].get<double>(),
             robust["samples"].get<std::size_t>(), robust["method"].get<std::string>(), robust["status"].get<std::string>());
  if (!robust["reason"].get<std::string>().empty()) fmt::print("{}\n", robust["reason"].get<std::string>());
  for (const char* which : {"nominal_optimum", "design"}) {
    const nlohmann::json& d = robust[which];
    if (d.is_null()) continue;
    fmt::print("  {:<16} n {}, D1 {:.6g} um, D2 {:.6g} um, w {:.6g} um, L {:.6g} um: PI {:.6e} 1/um, P(success) "
               "{:.4f} [{:.4f}, {:.4f}]\n",
               which, d["needles_per_row"].get<int>(), d["tip_diameter_um"].get<double>(),
               d["base_diameter_um"].get<double>(), d["width_um"].get<double>(), d["length_um"].get<double>(),
               d["performance_index_per_um"].get<double>(), d["success_probability"].get<double>(),
               d["success_ci95"][0].get<double>(), d["success_ci95"][1].get<double>());
  }
  if (!robust["index_cost_per_um"].is_null()) {
    fmt::print("  robustness costs {:.4g} 1/um of index ({:.3g} %), {} candidates checked\n",
               robust["index_cost_per_um"].get<double>(), robust["index_cost_percent"].get<double>(),
               robust["candidates_checked"].get<std::size_t>());
  }
}

// min_success_probability: the best nominal design that works on at least that fraction of the skin.
void run_robust(const OptimizeArguments& arguments, const io::SpaceFile& file, analysis::OptimizerOptions optimizer) {
  if (arguments.certified) {
    throw InvalidInput(fmt::format("{}: --certified does not apply with min_success_probability (robust design ranks "
                                   "the grid by brute force)",
                                   arguments.space_path));
  }
  io::RobustDesignRunOptions options;
  options.optimizer = optimizer;
  options.top = arguments.top;
  options.threads = arguments.threads;
  ProgressBar progress("optimize (robust)");
  options.progress = [&progress](double fraction) {  // Ctrl-C stops the run
    progress.update(fraction);
    return !interrupt_requested();
  };
  nlohmann::json json;
  try {
    json = io::robust_design_run_json(file, options);
  } catch (const InvalidInput& error) {
    throw InvalidInput(fmt::format("{}: {}", arguments.space_path, error.what()));
  }
  progress.finish();
  if (!arguments.out_path.empty()) io::write_text_file_atomically(arguments.out_path, io::json_text(json));
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_robust(json["robust"]);
  }
}

void run_optimize(const OptimizeArguments& arguments) {
  const io::SpaceFile file = io::read_space_file(arguments.space_path);
  const analysis::DesignSpace& space = file.space;
  analysis::OptimizerOptions options;
  options.method = arguments.certified ? analysis::SearchMethod::Certified : analysis::SearchMethod::BruteForce;
  options.top = arguments.top;
  options.published_compat = arguments.published_compat;
  options.threads = arguments.threads;
  options.max_brute_force_points = arguments.max_grid_points;
  options.max_memory_bytes = arguments.max_memory_gib * (1ULL << 30);
  if (file.robust) return run_robust(arguments, file, options);
  ProgressBar progress("optimize");
  options.progress = [&progress](double fraction) {  // from worker threads: the bar draws, Ctrl-C cancels
    progress.update(fraction);
    return !interrupt_requested();
  };
  analysis::OptimizerResult result;
  try {
    result = analysis::optimize_design(space, options);
  } catch (const InvalidInput& error) {
    throw InvalidInput(fmt::format("{}: {}", arguments.space_path, error.what()));
  }
  progress.finish();  // after Ctrl-C: throws Interrupted, nothing written

  const nlohmann::json json = io::optimizer_json(space, result);
  if (!arguments.out_path.empty()) io::write_text_file_atomically(arguments.out_path, io::json_text(json));
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_table(space, result);
  }
}

}  // namespace

void add_optimize_command(CLI::App& app) {
  auto arguments = std::make_shared<OptimizeArguments>();
  CLI::App* command = app.add_subcommand(
      "optimize", "Best array of one needle type over a grid of n, D1, D2, D3, w, L (dissertation §4.8, Table 6.3)");
  command->add_option("SPACE", arguments->space_path, "design-space file (TOML), format below")->required();
  command->add_flag("--json", arguments->json, "print the result as one JSON object (units in the key names)");
  command->add_option("--top", arguments->top, "number of designs to report, >= 1 (--certified reports only the best)")
      ->type_name("K")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_flag("--published-compat", arguments->published_compat,
                    "reproduce Table 6.3's hollow cylinder and hollow cone rows: the index uses the pitch w_max/n");
  command->add_flag("--certified", arguments->certified,
                    "branch-and-bound: the exact optimum without enumerating the grid; needed above "
                    "--max-grid-points (e.g. 1 um steps)");
  command
      ->add_option("--max-grid-points", arguments->max_grid_points,
                   "refuse a brute-force grid of more points (core/limits.hpp; about 100 s at 1e8 points/s)")
      ->type_name("N")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      ->add_option("--max-memory-gib", arguments->max_memory_gib,
                   "refuse a space whose tables would take more memory, in GiB (core/limits.hpp)")
      ->type_name("GIB")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--threads", arguments->threads, "worker threads, >= 0 (0: all hardware threads)")
      ->type_name("N")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--out", arguments->out_path, "also write the JSON result to FILE (written only on success)")
      ->type_name("FILE");
  command->footer(space_file_help() + "\n" + kRobustSpaceHelp);
  command->callback([arguments] { run_optimize(*arguments); });
}

}  // namespace needlekit::cli
