// `needlekit evaluate DESIGN.toml`: the performance index of one needle array with every intermediate quantity.
#include <fmt/format.h>

#include <memory>
#include <string>

#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/design_evaluation.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/result_writers.hpp"
#include "terminal_warnings.hpp"

namespace needlekit::cli {
namespace {

struct EvaluateArguments {
  std::string design_path;
  bool json = false;
  std::string out_path;
};

void print_row(std::string_view label, std::string_view value) { fmt::print("  {:<42}{}\n", label, value); }

std::string check_mark(bool ok) { return ok ? "ok" : "FAILS"; }

void print_table(const io::DesignFile& file, const analysis::PerformanceIndexResult& r) {
  const analysis::ArrayDesign& design = file.design;
  const needle::NeedleGeometry& n = design.needle;
  const double deg = 180 / M_PI;

  print_row("needle", fmt::format("{} {}, D1 = {:.6g} um, D2 = {:.6g} um{}, L = {:.6g} um",
                                  n.hollow() ? "hollow" : "solid", needle::to_string(n.shape), n.tip_diameter * 1e6,
                                  n.base_diameter * 1e6,
                                  n.hollow() ? fmt::format(", D3 = {:.6g} um", n.bore_diameter * 1e6) : "",
                                  n.length * 1e6));
  print_row("material", fmt::format("{}, E = {:.6g} GPa", design.material.name, design.material.youngs_modulus * 1e-9));
  print_row("array", fmt::format("{0} x {0} needles, w = {1:.6g} um, pitch Pxy = w/n = {2:.6g} um",
                                 design.needles_per_row, design.width * 1e6, r.pitch * 1e6));
  print_row("insertion", fmt::format("{} (alpha = {:.6g} N, tau = {:.6g} /mm), angle {:.6g} deg, target depth T = "
                                     "{:.6g} um",
                                     file.conditions.tissue.name, file.conditions.tissue.alpha,
                                     file.conditions.tissue.tau * 1e-3, file.conditions.angle * deg,
                                     file.conditions.target_depth * 1e6));
  fmt::print("\n");
  print_row("tip area A", fmt::format("{:.6g} um^2", r.tip_area * 1e12));
  print_row("puncture force law", fmt::format("{} ({})", analysis::to_string(r.puncture_force_law),
                                              analysis::puncture_force_law_source(r.puncture_force_law)));
  print_row("puncture force F(A)", fmt::format("{:.6g} N{}", r.puncture_force,
                                               r.puncture_force_in_range ? "" : "  (outside the law's range: note)"));
  print_row("deformation d (Eq 4.3)", fmt::format("{:.6g} um{}", r.deformation * 1e6,
                                                  r.small_tip_branch ? " (small-tip line d = K*A)" : ""));
  print_row("cutting depth h = L - d (Eq 4.4)", fmt::format("{:.6g} um", r.cutting_depth * 1e6));
  print_row("permeation depth H (Eq 4.23)", fmt::format("{:.6g} um", r.permeation_depth * 1e6));
  print_row("diameter at skin surface b", fmt::format("{:.6g} um", r.diameter_at_surface * 1e6));
  print_row("embedded volume (Table 4.2)", fmt::format("{:.6g} um^3", r.embedded_volume * 1e18));
  print_row("Q = volume / h (Table 4.4)", fmt::format("{:.6g} um^2", r.q_factor * 1e12));
  print_row("hole / gap volume (Eqs 4.20-4.22)",
            fmt::format("{:.6g} um^3 / {:.6g} um^3", r.hole_volume * 1e18, r.gap_volume * 1e18));
  print_row("fractional skin volume f_v", fmt::format("{:.6g}", r.fractional_skin_volume));
  print_row("needle volume", fmt::format("{:.6g} um^3", r.needle_volume * 1e18));
  print_row("critical buckling load P_cr", fmt::format("{:.6g} N ({}, {}, K = {:g}{})", r.buckling.critical_load,
                                                        analysis::to_string(r.buckling.method),
                                                        analysis::to_string(r.buckling.end_condition),
                                                        r.buckling.effective_length_factor,
                                                        r.buckling.method == analysis::BucklingMethod::TaperedEigenvalue
                                                            ? fmt::format(", m = {:.6g}", r.buckling.tapered_factor)
                                                            : ""));
  print_row("buckling force |F|/cos(theta)",
            fmt::format("{:.6g} N  {}", r.buckling_force, check_mark(r.buckling_ok)));
  print_row("critical bending load P_Be (Eq 5.7/5.8)",
            r.critical_bending_load ? fmt::format("{:.6g} N", *r.critical_bending_load) : "not assessed");
  print_row("bending force |F| tan(theta)",
            fmt::format("{:.6g} N  {}", r.bending_force, r.bending_ok ? check_mark(*r.bending_ok) : "not assessed"));
  print_row("performance index PI (Eq 4.25)", fmt::format("{:.6g} 1/um", r.performance_index * 1e-6));
  print_row("status", analysis::to_string(r.status));
  print_row("reason", r.reason.empty() ? "-" : r.reason);
  for (const std::string& note : r.notes) print_row("note", note);
}

void run_evaluate(const EvaluateArguments& arguments) {
  const io::DesignFile file = io::read_design_file(arguments.design_path);
  const io::DesignEvaluation evaluation = io::evaluate_design(file);
  print_warnings(evaluation.warnings);
  const nlohmann::json& json = evaluation.json;
  if (!arguments.out_path.empty()) io::write_text_file_atomically(arguments.out_path, io::json_text(json));
  if (arguments.json) {
    fmt::print("{}", io::json_text(json));
  } else {
    print_table(file, evaluation.result);
  }
}

}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto arguments = std::make_shared<EvaluateArguments>();
  CLI::App* command = app.add_subcommand(
      "evaluate", "Performance index of one needle array, with every intermediate quantity (dissertation ch. 4-5)");
  command->add_option("DESIGN", arguments->design_path, "design file (TOML), format below")->required();
  command->add_flag("--json", arguments->json, "print the result as one JSON object (units in the key names)");
  command->add_option("--out", arguments->out_path, "also write the JSON result to FILE (written only on success)")
      ->type_name("FILE");
  command->footer(design_file_help());
  command->callback([arguments] { run_evaluate(*arguments); });
}

}  // namespace needlekit::cli
