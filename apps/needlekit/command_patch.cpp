// `needlekit patch CASE.toml`: fit a rigid or flexible microneedle patch onto a body surface and evaluate every
// needle (dissertation ch. 5, §6.4); `--sweep max_spring_energy=A:B:N` writes the Fig 6.25 curve.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "file_format_help.hpp"
#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/mesh_attribution.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/io/patch_view.hpp"
#include "needlekit/io/patch_run.hpp"
#include "needlekit/io/patch_writers.hpp"
#include "needlekit/io/view_page.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/patch/fit_and_evaluate.hpp"
#include "progress_bar.hpp"
#include "terminal_warnings.hpp"
#include "viewer_sources.hpp"

namespace needlekit::cli {
namespace {

struct PatchArguments {
  std::string case_path;
  bool json = false;
  std::string out_dir;
  std::string sweep;
};

struct Sweep {
  double from = 0, to = 0;
  int count = 0;
};

// "max_spring_energy=0.005mJ:0.05mJ:10"
Sweep parse_sweep(const std::string& text) {
  const std::string prefix = "max_spring_energy=";
  const std::string expected = "expected max_spring_energy=FROM:TO:COUNT, e.g. max_spring_energy=0.005mJ:0.05mJ:10";
  if (text.rfind(prefix, 0) != 0) throw InvalidInput(fmt::format("--sweep: '{}' is not a sweep, {}", text, expected));
  std::stringstream rest(text.substr(prefix.size()));
  std::string from, to, count;
  if (!std::getline(rest, from, ':') || !std::getline(rest, to, ':') || !std::getline(rest, count) ||
      count.find(':') != std::string::npos) {
    throw InvalidInput(fmt::format("--sweep: '{}' is not FROM:TO:COUNT, {}", text, expected));
  }
  Sweep sweep;
  sweep.from = units::parse_quantity(from, units::Dimension::Energy, "--sweep (from)");
  sweep.to = units::parse_quantity(to, units::Dimension::Energy, "--sweep (to)");
  try {
    std::size_t used = 0;
    sweep.count = std::stoi(count, &used);
    if (used != count.size()) throw std::invalid_argument(count);
  } catch (const std::exception&) {
    throw InvalidInput(fmt::format("--sweep: count '{}' is not an integer, {}", count, expected));
  }
  if (!(sweep.from > 0) || !(sweep.to >= sweep.from) || sweep.count < 1 || sweep.count > 10000 ||
      (sweep.count == 1 && sweep.to != sweep.from)) {
    throw InvalidInput(fmt::format("--sweep: '{}' is out of range, expected 0 < FROM <= TO and COUNT in [1, 10000] "
                                   "(COUNT >= 2 when FROM < TO)",
                                   text));
  }
  return sweep;
}

void print_summary(const io::PatchCase& c, const nlohmann::json& s) {
  auto row = [](std::string_view label, const std::string& value) { fmt::print("  {:<34}{}\n", label, value); };
  auto range = [](const nlohmann::json& j, std::string_view unit) {
    if (j.is_null()) return std::string("-");
    return fmt::format("{:.4g} .. {:.4g} {} (mean {:.4g})", j["min"].get<double>(), j["max"].get<double>(), unit,
                       j["mean"].get<double>());
  };
  row("surface", fmt::format("{} (x {:.6g} m per unit)", c.mesh.string(), c.mesh_unit));
  row("patch", fmt::format("{} {} x {} mm, {} x {} needles, k = {:.4g} N/mm", s["kind"].get<std::string>(),
                           c.design.width_u * 1e3, c.design.width_v * 1e3, c.design.needles_u, c.design.needles_v,
                           c.design.stiffness_u * 1e-3));
  row("fit", fmt::format("{} in {:.3g} ms{}", s["status"].get<std::string>(), s["fit_ms"].get<double>(),
                         s["reason"].get<std::string>().empty() ? "" : ": " + s["reason"].get<std::string>()));
  row("F(A) / d", fmt::format("{:.4g} N / {:.4g} um", s["puncture_force_N"].get<double>(),
                              s["deformation_um"].get<double>()));
  row("critical loads P_cr / P_Be",
      fmt::format("{:.4g} N / {}", s["critical_buckling_load_N"].get<double>(),
                  s["critical_bending_load_N"].is_null() ? "not assessed"
                                                         : fmt::format("{:.4g} N", s["critical_bending_load_N"].get<double>())));
  row("needles penetrating/buckled/bent", fmt::format("{} / {} / {} of {}", s["penetrating"].get<int>(),
                                                      s["buckled"].get<int>(), s["bent"].get<int>(),
                                                      s["needles"].get<int>()));
  row("angle", range(s["angle_deg"], "deg"));
  row("buckling force |F|/cos", range(s["buckling_force_N"], "N"));
  row("bending force |F| tan", range(s["bending_force_N"], "N"));
  row("travel x (Eq 5.12)", range(s["travel_um"], "um"));
  row("performance index", fmt::format("{} (total {:.4g} 1/um)", range(s["performance_index_per_um"], "1/um"),
                                       s["performance_index_total_per_um"].get<double>()));
  row("|geodesic - rest| / rest", s["spring_geodesic_strain"].is_null()
                                      ? "-"
                                      : fmt::format("max {:.3g}, mean {:.3g} ({} not converged)",
                                                    s["spring_geodesic_strain"]["max"].get<double>(),
                                                    s["spring_geodesic_strain"]["mean"].get<double>(),
                                                    s["spring_geodesics_not_converged"].get<int>()));
  row("spring energy (Eq 5.13)", s["spring_energy_mJ"].is_null()
                                     ? "-"
                                     : fmt::format("total {:.4g} mJ, max {:.4g} mJ",
                                                   s["spring_energy_mJ"]["total"].get<double>(),
                                                   s["spring_energy_mJ"]["max"].get<double>()));
}

// --sweep: the flexible fit at each E_cri of the sweep, as CSV (printed, and with --out sweep.csv and sweep.json).
// Returns whether a fit did not converge.
bool run_sweep(const PatchArguments& arguments, const Sweep& sweep, const geometry::SurfaceMesh& surface,
               const io::PatchCase& c, patch::FitAndEvaluateOptions options) {
  bool not_converged = false;
  std::string csv =
      "max_spring_energy_mJ,performance_index_mean_per_um,performance_index_total_per_um,penetrating,buckled,bent,"
      "angle_max_deg,buckling_force_max_N,bending_force_max_N,bending_force_mean_N,spring_energy_total_mJ,fit_ms,"
      "status\n";
  nlohmann::json points = nlohmann::json::array();
  ProgressBar progress("sweep");
  for (int i = 0; i < sweep.count; ++i) {
    options.fit.flexible.max_spring_energy =
        sweep.count == 1 ? sweep.from : sweep.from + (sweep.to - sweep.from) * i / (sweep.count - 1);
    const patch::FitAndEvaluateResult r = patch::fit_and_evaluate(surface, c.design, options);
    // The output folder once the first fit placed the patch (a bad placement leaves none), before the long sweep.
    if (i == 0 && !arguments.out_dir.empty()) create_output_directory(arguments.out_dir);
    const patch::PatchEvaluation& e = r.evaluation;
    const double ms = r.fit_seconds * 1e3;
    not_converged = not_converged || r.status == patch::FitStatus::NotConverged;
    points.push_back(io::patch_summary_json(r.design, options.fit, r.fit, e, ms));
    csv += fmt::format("{:.6g},{:.6g},{:.6g},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.4g},{}\n",
                       options.fit.flexible.max_spring_energy * 1e3, e.performance_index.mean * 1e-6,
                       e.performance_index.total * 1e-6, e.penetrating, e.buckled, e.bent, e.angle.max * 180 / M_PI,
                       e.buckling_force.max, e.bending_force.max, e.bending_force.mean, e.spring_energy.total * 1e3,
                       ms, patch::to_string(r.status));
    progress.update(static_cast<double>(i + 1) / sweep.count);
  }
  progress.finish();
  if (!arguments.out_dir.empty()) {  // both files or none
    StagedFiles outputs;
    outputs.write(std::filesystem::path(arguments.out_dir) / "sweep.csv", csv);
    outputs.write(std::filesystem::path(arguments.out_dir) / "sweep.json", io::json_text(points));
    outputs.commit();
  }
  if (arguments.json) {
    fmt::print("{}", io::json_text(points));
  } else {
    fmt::print("{}", csv);
  }
  return not_converged;
}

// One fit's files: the needles' table, the surface, patch and needles for ParaView, the attribution of the body
// mesh, the summary and the 3D view (every file or none: StagedFiles writes temporary names, renamed at the end).
void write_fit_outputs(const PatchArguments& arguments, const io::PatchCase& c, const io::PatchSurface& body,
                       const patch::FitAndEvaluateResult& r, const nlohmann::json& summary) {
  const geometry::SurfaceMesh& surface = body.surface;
  const std::filesystem::path out(arguments.out_dir);
  // Created only now: a placement that fails (bad input, exit 2) leaves no folder behind. A fit takes milliseconds.
  create_output_directory(out);
  const double diagonal = std::hypot(r.design.width_u, r.design.width_v);
  StagedFiles outputs;
  outputs.write(out / "needles.csv", io::patch_needles_csv(r.design, r.fit, r.evaluation));
  outputs.write(out / "surface.vtu",
                io::vtu_document(io::surface_grid(surface, r.frame.surface_point, diagonal), out / "surface.vtu"));
  outputs.write(out / "patch.vtu",
                io::vtu_document(io::patch_grid(r.design, r.fit, r.geodesics->strain), out / "patch.vtu"));
  outputs.write(out / "needles.vtu", io::vtu_document(io::needles_grid(r.evaluation), out / "needles.vtu"));
  if (const std::optional<io::MeshAttribution>& attribution = body.attribution) {
    outputs.write(out / "ATTRIBUTION.md",
                  fmt::format("surface.vtu is a part of {} ({}).\n\n- {}\n\n{}\n", c.mesh.filename().string(),
                              attribution->readme.lexically_normal().string(), fmt::join(attribution->entries, "\n- "),
                              fmt::join(attribution->notices, "\n")));
  }
  outputs.write(out / "summary.json", io::json_text(summary));
  // The 3D view (docs/views.md): the surface, the patch and the needles coloured by force or margin.
  const std::string name = std::filesystem::path(arguments.case_path).stem().string();
  outputs.write(out / "patch_view.js", io::view_script(io::patch_view(name, surface, r.design, r.fit, r.evaluation)));
  io::stage_view_page(outputs, out, "patch_view.html", name + ": 3D view", {"patch_view.js"},
                      io::viewer_files(viewer_sources()));
  outputs.commit();
}

void run_patch(const PatchArguments& arguments) {
  io::PatchCase c = io::read_patch_case(arguments.case_path);
  const bool sweeping = !arguments.sweep.empty();
  const Sweep sweep = sweeping ? parse_sweep(arguments.sweep) : Sweep{};
  if (sweeping && c.fit.kind != patch::PatchKind::Flexible) {
    throw InvalidInput(fmt::format("--sweep max_spring_energy needs a flexible patch, but {} has patch.kind = \"{}\"",
                                   arguments.case_path, patch::to_string(c.fit.kind)));
  }
  // Warnings: an inward surface turned outwards, implausible scales (a unit mistake?) and a mesh without a licence or
  // attribution.
  const io::PatchSurface body = io::read_patch_surface(c);
  const patch::FitAndEvaluateOptions options{c.placement, c.fit, c.evaluation, !sweeping, nullptr};
  print_warnings(body.warnings);
  // A fit that did not converge (the equilibrium solver's iteration limit) ends the command with exit code 3 once
  // everything is written; the other statuses (the patch leaves the surface, springs over E_cri) are outcomes.
  if (sweeping) {
    if (run_sweep(arguments, sweep, body.surface, c, options)) throw CommandOutcome{ExitCode::NumericalFailure};
    return;
  }
  const patch::FitAndEvaluateResult r = patch::fit_and_evaluate(body.surface, c.design, options);
  const nlohmann::json summary = io::patch_case_summary(c, r, body.warnings);
  if (!arguments.out_dir.empty()) write_fit_outputs(arguments, c, body, r, summary);
  if (arguments.json) {
    fmt::print("{}", io::json_text(summary));
  } else {
    print_summary(c, summary);
  }
  if (r.status == patch::FitStatus::NotConverged) throw CommandOutcome{ExitCode::NumericalFailure};
}

}  // namespace

void add_patch_command(CLI::App& app) {
  auto arguments = std::make_shared<PatchArguments>();
  CLI::App* command = app.add_subcommand(
      "patch", "Fit a rigid or flexible microneedle patch onto a body surface and evaluate every needle (ch. 5, 6.4)");
  command->add_option("CASE", arguments->case_path, "patch case file (TOML), format below")->required();
  command->add_flag("--json", arguments->json, "print the summary (or the sweep) as JSON, units in the key names");
  command->add_option("--out", arguments->out_dir,
                      "write needles.csv, summary.json, surface.vtu, patch.vtu, needles.vtu (ParaView), the 3D view "
                      "patch_view.html (docs/views.md) and ATTRIBUTION.md into DIR; with --sweep: sweep.csv and "
                      "sweep.json")
      ->type_name("DIR");
  command->add_option("--sweep", arguments->sweep,
                      "sweep the flexible patch's spring-energy cap, e.g. max_spring_energy=0.005mJ:0.05mJ:10 "
                      "(the Fig 6.25 curve)")
      ->type_name("SPEC");
  command->footer(patch_case_help());
  command->callback([arguments] { run_patch(*arguments); });
}

}  // namespace needlekit::cli
