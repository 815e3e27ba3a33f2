// `needlekit patch CASE.toml`: fit a rigid or flexible microneedle patch onto a body surface and evaluate every
// needle (dissertation ch. 5, §6.4); `--sweep max_spring_energy=A:B:N` writes the Fig 6.25 curve.
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/io/patch_writers.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/patch/spring_geodesics.hpp"
#include "progress_bar.hpp"

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

// The attribution section of the mesh folder's README.md (kept wherever the meshes or renderings are shipped).
std::string attribution_of(const std::filesystem::path& mesh) {
  std::ifstream in(mesh.parent_path() / "README.md");
  if (!in) return {};
  std::string line, text;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) inside = line.find("ttribution") != std::string::npos;
    if (inside) text += line + "\n";
  }
  return text;
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

void run_patch(const PatchArguments& arguments) {
  io::PatchCase c = io::read_patch_case(arguments.case_path);
  const bool sweeping = !arguments.sweep.empty();
  const Sweep sweep_spec = sweeping ? parse_sweep(arguments.sweep) : Sweep{};
  const Sweep* sweep = sweeping ? &sweep_spec : nullptr;
  if (sweep && c.fit.kind != patch::PatchKind::Flexible) {
    throw InvalidInput(fmt::format("--sweep max_spring_energy needs a flexible patch, but {} has patch.kind = \"{}\"",
                                   arguments.case_path, patch::to_string(c.fit.kind)));
  }
  const patch::PatchDesign design = patch::patch_design(c.design);
  geometry::BodySurface body = geometry::read_body_surface(c.mesh, c.mesh_unit);
  if (body.flipped) fmt::print("note: {}\n", body.note);
  geometry::SurfaceMesh surface = std::move(body.surface);
  const double diagonal = std::hypot(design.width_u, design.width_v);
  const patch::PatchFrame frame = patch::patch_frame(surface, c.placement, diagonal, design.needle.length);

  auto run_once = [&](const patch::FitOptions& options, double& ms) {
    const auto start = std::chrono::steady_clock::now();
    patch::FittedPatch fit = patch::fit_patch(surface, design, frame, options);
    ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return fit;
  };

  if (sweep) {
    std::string csv =
        "max_spring_energy_mJ,performance_index_mean_per_um,performance_index_total_per_um,penetrating,buckled,bent,"
        "angle_max_deg,buckling_force_max_N,bending_force_max_N,bending_force_mean_N,spring_energy_total_mJ,fit_ms,"
        "status\n";
    nlohmann::json points = nlohmann::json::array();
    ProgressBar progress("sweep");
    for (int i = 0; i < sweep->count; ++i) {
      patch::FitOptions options = c.fit;
      options.flexible.max_spring_energy =
          sweep->count == 1 ? sweep->from : sweep->from + (sweep->to - sweep->from) * i / (sweep->count - 1);
      double ms = 0;
      const patch::FittedPatch fit = run_once(options, ms);
      const patch::PatchEvaluation e = patch::evaluate_needles(surface, design, fit, c.evaluation);
      const nlohmann::json s = io::patch_summary_json(design, options, fit, e, ms);
      points.push_back(s);
      csv += fmt::format("{:.6g},{:.6g},{:.6g},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.4g},{}\n",
                         options.flexible.max_spring_energy * 1e3, e.performance_index.mean * 1e-6,
                         e.performance_index.total * 1e-6, e.penetrating, e.buckled, e.bent, e.angle.max * 180 / M_PI,
                         e.buckling_force.max, e.bending_force.max, e.bending_force.mean, e.spring_energy.total * 1e3,
                         ms, patch::to_string(fit.status));
      progress.update(static_cast<double>(i + 1) / sweep->count);
    }
    progress.finish();
    if (!arguments.out_dir.empty()) {
      std::filesystem::create_directories(arguments.out_dir);
      io::write_text_file_atomically(std::filesystem::path(arguments.out_dir) / "sweep.csv", csv);
      io::write_text_file_atomically(std::filesystem::path(arguments.out_dir) / "sweep.json", points.dump(2) + "\n");
    }
    if (arguments.json) {
      fmt::print("{}\n", points.dump(2));
    } else {
      fmt::print("{}", csv);
    }
    return;
  }

  double ms = 0;
  const patch::FittedPatch fit = run_once(c.fit, ms);
  const patch::PatchEvaluation evaluation = patch::evaluate_needles(surface, design, fit, c.evaluation);
  nlohmann::json summary = io::patch_summary_json(design, c.fit, fit, evaluation, ms);
  // Beyond the dissertation: the springs measured along the surface (exact geodesic distances).
  const patch::SpringGeodesics geodesics = patch::spring_geodesics(surface, design, fit);
  summary["spring_geodesic_strain"] =
      geodesics.strain_abs.count == 0
          ? nlohmann::json(nullptr)
          : nlohmann::json{{"max", geodesics.strain_abs.max}, {"mean", geodesics.strain_abs.mean}};
  summary["spring_geodesics_not_converged"] = geodesics.not_converged;
  if (!arguments.out_dir.empty()) {
    const std::filesystem::path out(arguments.out_dir);
    std::error_code error;
    std::filesystem::create_directories(out, error);
    if (error) throw IoError(fmt::format("{}: cannot create the output folder: {}", out.string(), error.message()));
    const io::VtuGrid surface_part = io::surface_grid(surface, frame.surface_point, diagonal);
    const io::VtuGrid patch_part = io::patch_grid(design, fit, geodesics.strain);
    const io::VtuGrid needles_part = io::needles_grid(evaluation);
    io::write_text_file_atomically(out / "needles.csv", io::patch_needles_csv(design, fit, evaluation));
    io::write_text_file_atomically(out / "summary.json", summary.dump(2) + "\n");
    io::write_vtu(surface_part, out / "surface.vtu");
    io::write_vtu(patch_part, out / "patch.vtu");
    io::write_vtu(needles_part, out / "needles.vtu");
    const std::string attribution = attribution_of(c.mesh);
    if (!attribution.empty()) {
      io::write_text_file_atomically(out / "ATTRIBUTION.md",
                                     fmt::format("surface.vtu is a part of {}.\n\n{}", c.mesh.filename().string(),
                                                 attribution));
    }
  }
  if (arguments.json) {
    fmt::print("{}\n", summary.dump(2));
  } else {
    print_summary(c, summary);
  }
}

}  // namespace

void add_patch_command(CLI::App& app) {
  auto arguments = std::make_shared<PatchArguments>();
  CLI::App* command = app.add_subcommand(
      "patch", "Fit a rigid or flexible microneedle patch onto a body surface and evaluate every needle (ch. 5, 6.4)");
  command->add_option("CASE", arguments->case_path, "patch case file (TOML), format below")->required();
  command->add_flag("--json", arguments->json, "print the summary (or the sweep) as JSON, units in the key names");
  command->add_option("--out", arguments->out_dir,
                      "write needles.csv, summary.json, surface.vtu, patch.vtu, needles.vtu (ParaView) and "
                      "ATTRIBUTION.md into DIR; with --sweep: sweep.csv and sweep.json")
      ->type_name("DIR");
  command->add_option("--sweep", arguments->sweep,
                      "sweep the flexible patch's spring-energy cap, e.g. max_spring_energy=0.005mJ:0.05mJ:10 "
                      "(the Fig 6.25 curve)")
      ->type_name("SPEC");
  command->footer(
      "Case file (quantities are strings with units):\n"
      "  [surface]  mesh = \"neck.obj\" (OBJ/STL/PLY/OFF, relative to the case file); unit = \"m\" | \"mm\" | \"15.8 mm\";\n"
      "             center_vertex = 2243 or center = [\"x mm\", \"y mm\", \"z mm\"]; rotation = \"0 deg\";\n"
      "             approach = \"-z\" (default) | \"normal\"\n"
      "  [patch]    kind = \"rigid\" | \"flexible\" | \"equilibrium\"; size = \"10 mm\"; needles_per_row = 10;\n"
      "             spring_constant = \"1 N/mm\" or { u = , v = , diagonal = }; max_spring_energy = \"0.05 mJ\";\n"
      "             first_node = \"first-contact\" | \"corner\"; walk = \"cutting-plane\" | \"unfolding\";\n"
      "             load = \"0.0712 N\" (equilibrium: force per node)\n"
      "  [needle], [tissue], [insertion]  as in design files (see needlekit evaluate --help)");
  command->callback([arguments] { run_patch(*arguments); });
}

}  // namespace needlekit::cli
