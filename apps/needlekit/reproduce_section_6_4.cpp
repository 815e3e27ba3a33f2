// §6.4 of `needlekit reproduce`: rigid vs flexible patch on the neck (Figs 6.21-6.24), the energy sweep (Fig 6.25),
// the colour maps of Fig 6.26 and the skull patches of Fig 6.27, on the body surface meshes of the patch examples.
// The forces that follow from F(A) and the angle alone (Eqs 4.2, 5.3, 5.4) are checked against the printed ones.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <optional>
#include <tuple>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/mesh_attribution.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/io/patch_writers.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/io/patch_view.hpp"
#include "needlekit/patch/fit_and_evaluate.hpp"
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {
namespace {

constexpr double kMicro = 1e-6;

const std::vector<std::string>& patch_examples() {
  static const std::vector<std::string> examples = {"patch_neck_rigid.toml", "patch_neck_flexible.toml",
                                                    "patch_neck_20mm.toml",  "patch_neck_20mm_50um.toml",
                                                    "patch_skull.toml",      "patch_skull_20mm.toml"};
  return examples;
}

// The case file with the mesh taken from --meshes when given.
io::PatchCase read_case(const RunContext& context, const std::string& example) {
  io::PatchCase c = io::read_patch_case(context.example(example));
  if (!context.meshes.empty()) c.mesh = context.meshes / c.mesh.filename();
  return c;
}

// The attribution lines of the mesh folder's README.md that name this mesh (kept under its renderings).
std::string attribution_of(const std::filesystem::path& mesh) {
  const std::optional<io::MeshAttribution> attribution = io::mesh_attribution(mesh);
  if (!attribution) return fmt::format("Mesh: {} ({})", mesh.filename().string(), io::missing_attribution_warning(mesh));
  return fmt::format("Mesh attribution: {}", fmt::join(attribution->entries, " "));
}

// Loaded surfaces, by file and unit (the neck is used by four examples).
class Surfaces {
public:
  const geometry::SurfaceMesh& get(const io::PatchCase& c) {
    const std::string key = fmt::format("{}|{}", c.mesh.string(), c.mesh_unit);
    auto found = surfaces_.find(key);
    if (found == surfaces_.end()) {
      auto surface =
          std::make_unique<geometry::SurfaceMesh>(geometry::read_body_surface(c.mesh, c.mesh_unit).surface);
      found = surfaces_.emplace(key, std::move(surface)).first;
    }
    return *found->second;
  }

private:
  std::map<std::string, std::unique_ptr<geometry::SurfaceMesh>> surfaces_;
};

struct PatchRun {
  std::string example;
  io::PatchCase input;
  patch::PatchDesign design;
  patch::FittedPatch fit;
  patch::PatchEvaluation evaluation;
  nlohmann::json summary;
  double fit_ms = 0;
  int surface_triangles = 0;
};

PatchRun run_patch(const RunContext& context, Surfaces& surfaces, const std::string& example,
                   std::optional<double> max_spring_energy = std::nullopt) {
  PatchRun run;
  run.example = example;
  run.input = read_case(context, example);
  if (max_spring_energy) run.input.fit.flexible.max_spring_energy = *max_spring_energy;
  const geometry::SurfaceMesh& surface = surfaces.get(run.input);
  run.surface_triangles = surface.triangle_count();
  patch::FitAndEvaluateResult result = patch::fit_and_evaluate(
      surface, run.input.design, {run.input.placement, run.input.fit, run.input.evaluation, false, nullptr});
  run.design = std::move(result.design);
  run.fit = std::move(result.fit);
  run.evaluation = std::move(result.evaluation);
  run.fit_ms = result.fit_seconds * 1e3;
  run.summary = io::patch_summary_json(run.design, run.input.fit, run.fit, run.evaluation, run.fit_ms);
  return run;
}

std::string case_text(const PatchRun& run) {
  const patch::PatchDesign& d = run.design;
  const needle::NeedleGeometry& n = d.needle;
  return fmt::format("examples/{}: {} patch {:g} x {:g} mm, {} x {} {} needles (D1 = {:g} um, D2 = {:g} um, L = {:g} "
                     "um, {}), k = {:g} N/mm{}; surface {} ({} triangles); fit {} in {:.1f} ms{}",
                     run.example, patch::to_string(run.input.fit.kind), d.width_u * 1e3, d.width_v * 1e3, d.nodes_u,
                     d.nodes_v, needle::to_string(n.shape), n.tip_diameter / kMicro, n.base_diameter / kMicro,
                     n.length / kMicro, d.material.name, run.input.design.stiffness_u * 1e-3,
                     run.input.fit.kind == patch::PatchKind::Flexible
                         ? fmt::format(", E_cri = {:g} mJ", run.input.fit.flexible.max_spring_energy * 1e3)
                         : "",
                     run.input.mesh.filename().string(), run.surface_triangles,
                     patch::to_string(run.fit.status), run.fit_ms, run.fit.reason.empty() ? "" : ": " + run.fit.reason);
}

// Writes the per-needle CSV and the surface near the patch, and adds the three-panel rendering (buckling force,
// bending force, performance index) of Figs 6.21-6.27.
void render(const RunContext& context, SectionReport& report, Surfaces& surfaces, const PatchRun& run,
            const std::string& name, const std::string& caption) {
  const std::string needles = context.write(fmt::format("section_6_4/{}_needles.csv", name),
                                            io::patch_needles_csv(run.design, run.fit, run.evaluation));
  report.data_file(needles);
  report.data_file(context.write(fmt::format("section_6_4/{}_summary.json", name), io::json_text(run.summary)));
  // Surface triangles within the patch's reach, in mm.
  const geometry::SurfaceMesh& surface = surfaces.get(run.input);
  const Eigen::Vector3d center = run.fit.frame.surface_point;
  const double radius = 0.75 * std::hypot(run.design.width_u, run.design.width_v);
  const geometry::TriangleMesh& mesh = surface.mesh();
  nlohmann::json vertices = nlohmann::json::array(), triangles = nlohmann::json::array();
  std::map<int, int> index;
  for (const auto& t : mesh.triangles) {
    bool near = false;
    for (int k : t) near = near || (mesh.vertices[k] - center).norm() < radius;
    if (!near) continue;
    nlohmann::json tri = nlohmann::json::array();
    for (int k : t) {
      auto [it, added] = index.emplace(k, static_cast<int>(index.size()));
      if (added) vertices.push_back({mesh.vertices[k].x() * 1e3, mesh.vertices[k].y() * 1e3, mesh.vertices[k].z() * 1e3});
      tri.push_back(it->second);
    }
    triangles.push_back(tri);
  }
  const std::string surface_file = context.write(fmt::format("section_6_4/{}_surface.json", name),
                                                 io::rounded_numbers(nlohmann::json{{"unit", "mm"}, {"vertices", vertices},
                                                                                    {"triangles", triangles}})
                                                     .dump() + "\n");
  report.data_file(surface_file);
  add_view(context, report, fmt::format("6_4_{}", name),
           io::patch_view(name, surface, run.design, run.fit, run.evaluation),
           fmt::format("{} (click a needle for its numbers)", caption));
  report.figure(fmt::format("figures/{}.png", name), caption,
                {{"kind", "patch3d"},
                 {"csv", needles},
                 {"surface", surface_file},
                 {"panels", {{{"value", "buckling_force_N"}, {"colorbar", "buckling force |F|/cos(theta) (N)"}},
                             {{"value", "bending_force_N"}, {"colorbar", "bending force |F| tan(theta) (N)"}},
                             {{"value", "performance_index_per_um"}, {"colorbar", "performance index (1/um)"}}}}},
                attribution_of(run.input.mesh));
}

// The printed min/max/mean of a force beside needlekit's.
void compare_statistics(SectionReport& report, const PublishedValues& published, const std::string& prefix,
                        const std::string& quantity, const patch::Statistics& s, const std::string& label) {
  for (const auto& [end, value] : std::vector<std::pair<std::string, double>>{{"min", s.min}, {"max", s.max}, {"mean", s.mean}}) {
    report.compare(published.at(fmt::format("{}.{}_{}", prefix, quantity, end)), value,
                   fmt::format("{}: {} {} ({} needles on the surface)", label, end,
                               quantity == "buckling_force" ? "buckling force" : "bending force", s.count));
  }
}

// The forces that F(A) and θ determine: |F(A)| of a 70 um tip (the minimum buckling force, θ = 0, of every 70 um
// patch of §6.4) and the rigid patch's bending extremes from its buckling extremes (the same θ, Eqs 5.3/5.4).
void force_checks(const RunContext& context, SectionReport& report) {
  const PublishedValues& published = *context.published;
  analysis::ArrayDesign design;
  design.needle = {needle::Shape::Cylinder, 70e-6, 70e-6, 0, 400e-6};
  design.material = materials::material_preset("su-8");
  const analysis::PerformanceIndexResult straight = analysis::performance_index(design, {});
  report.compare(published.at("6.4.puncture_force_tip70"), std::abs(straight.puncture_force),
                 "|F(A)| of a 70 um tip (Eq 4.2): the buckling force at theta = 0", "");
  for (const char* end : {"min", "max"}) {
    const PublishedValue& buckling = published.at(fmt::format("6.4.1.rigid.buckling_force_{}", end));
    analysis::InsertionConditions conditions;
    conditions.angle = std::acos(std::abs(straight.puncture_force) / buckling.value);
    const analysis::PerformanceIndexResult r = analysis::performance_index(design, conditions);
    report.compare(published.at(fmt::format("6.4.1.rigid.bending_force_{}_from_buckling", end)), r.bending_force,
                   fmt::format("rigid patch: {} bending force |F| tan(theta) at the theta of the {} buckling force {} N",
                               end, end, buckling.printed),
                   fmt::format("theta = {:.2f} deg", conditions.angle * 180 / M_PI));
  }
}

void neck_rigid_vs_flexible(const RunContext& context, SectionReport& report, Surfaces& surfaces,
                            const SectionProgress& progress) {
  const PublishedValues& published = *context.published;
  const PatchRun rigid = run_patch(context, surfaces, "patch_neck_rigid.toml");
  progress(0.25, "§6.4.1 rigid");
  const PatchRun flexible = run_patch(context, surfaces, "patch_neck_flexible.toml");
  progress(0.35, "§6.4.1 flexible");
  for (const PatchRun* run : {&rigid, &flexible}) {
    const std::string kind = run == &rigid ? "rigid" : "flexible";
    report.input(case_text(*run));
    compare_statistics(report, published, "6.4.1." + kind, "buckling_force", run->evaluation.buckling_force,
                       "§6.4.1 " + kind + " patch");
    compare_statistics(report, published, "6.4.1." + kind, "bending_force", run->evaluation.bending_force,
                       "§6.4.1 " + kind + " patch");
    report.compare(published.at("6.4.1." + kind + ".performance_index_mean"), run->evaluation.performance_index.mean * kMicro,
                   "§6.4.1 " + kind + " patch: mean performance index", "needlekit: 1/um (Eq 5.9)");
    report.compare(published.at("6.4.1." + kind + ".performance_index_total"),
                   run->evaluation.performance_index.total * kMicro, "§6.4.1 " + kind + " patch: total performance index",
                   "needlekit: 1/um (Eq 5.9)");
  }
  render(context, report, surfaces, rigid, "fig_6_21_rigid_neck",
         "Fig 6.21: the rigid 10 x 10 mm patch fitted on the front of the neck, needles coloured by buckling force, "
         "bending force and performance index.");
  render(context, report, surfaces, flexible, "fig_6_23_flexible_neck",
         "Fig 6.23: the flexible 10 x 10 mm patch on the same spot: it follows the skin, so the needles meet it at "
         "smaller angles.");
  auto stat = [](const patch::Statistics& s, const char* which) {
    return std::string(which) == "min" ? s.min : s.max;
  };
  nlohmann::json categories = {"buckling min", "buckling max", "bending min", "bending max"};
  nlohmann::json series = nlohmann::json::array();
  for (const char* kind : {"rigid", "flexible"}) {
    const PatchRun& run = std::string(kind) == "rigid" ? rigid : flexible;
    series.push_back({{"label", fmt::format("{} (dissertation)", kind)},
                      {"values", {published.at(fmt::format("6.4.1.{}.buckling_force_min", kind)).value,
                                  published.at(fmt::format("6.4.1.{}.buckling_force_max", kind)).value,
                                  published.at(fmt::format("6.4.1.{}.bending_force_min", kind)).value,
                                  published.at(fmt::format("6.4.1.{}.bending_force_max", kind)).value}}});
    series.push_back({{"label", fmt::format("{} (needlekit)", kind)},
                      {"values", {stat(run.evaluation.buckling_force, "min"), stat(run.evaluation.buckling_force, "max"),
                                  stat(run.evaluation.bending_force, "min"), stat(run.evaluation.bending_force, "max")}}});
  }
  report.figure("figures/fig_6_24_rigid_vs_flexible.png",
                "Fig 6.24(b): extreme buckling and bending forces of the rigid and the flexible patch, dissertation and "
                "needlekit.",
                {{"kind", "bars"}, {"categories", categories}, {"series", series}, {"ylabel", "force (N)"}});
}

void neck_20mm(const RunContext& context, SectionReport& report, Surfaces& surfaces, const SectionProgress& progress) {
  const PublishedValues& published = *context.published;
  // Fig 6.25: mean index against the spring-energy cap, tips 70 and 50 um.
  const int points = context.quick ? 4 : 10;
  nlohmann::json series = nlohmann::json::array();
  for (const auto& [example, label, key] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"patch_neck_20mm.toml", "tip 70 um", "tip70"}, {"patch_neck_20mm_50um.toml", "tip 50 um", "tip50"}}) {
    nlohmann::json rows = nlohmann::json::array();
    double lowest = INFINITY, highest = -INFINITY;
    std::string text;
    for (int i = 0; i < points; ++i) {
      context.check_interrupt();
      const double energy = 0.005e-3 + (0.05e-3 - 0.005e-3) * i / (points - 1);
      const PatchRun run = run_patch(context, surfaces, example, energy);
      if (i == 0) text = case_text(run);
      const double mean = run.evaluation.performance_index.mean * kMicro;
      lowest = std::min(lowest, mean);
      highest = std::max(highest, mean);
      rows.push_back({energy * 1e3, mean, run.evaluation.performance_index.total * kMicro, run.evaluation.penetrating,
                      run.evaluation.buckling_force.max, run.evaluation.bending_force.max,
                      run.evaluation.spring_energy.total * 1e3, std::string(patch::to_string(run.fit.status))});
    }
    report.input(text + fmt::format(" (swept over E_cri = 0.005 .. 0.05 mJ, {} points)", points));
    report.compare(published.at("6.4.2." + key + ".performance_index_min"), lowest,
                   fmt::format("Fig 6.25 {}: lowest mean performance index over the sweep", label), "1/um");
    report.compare(published.at("6.4.2." + key + ".performance_index_max"), highest,
                   fmt::format("Fig 6.25 {}: highest mean performance index over the sweep", label), "1/um");
    const std::string data = context.write(
        fmt::format("section_6_4/fig_6_25_{}.csv", key),
        csv_text({"max_spring_energy_mJ", "performance_index_mean_per_um", "performance_index_total_per_um",
                  "penetrating", "buckling_force_max_N", "bending_force_max_N", "spring_energy_total_mJ", "status"},
                 rows));
    report.data_file(data);
    series.push_back({{"csv", data}, {"x", "max_spring_energy_mJ"}, {"y", "performance_index_mean_per_um"},
                      {"label", label}, {"style", "o-"}});
    progress(key == "tip70" ? 0.55 : 0.7, "Fig 6.25");
  }
  report.figure("figures/fig_6_25_energy_sweep.png",
                "Fig 6.25: mean performance index of the 20 x 20 mm flexible patch (400 cylindrical SU-8 needles, 400 um) "
                "on the neck against the spring-energy cap E_cri.",
                {{"kind", "lines"}, {"series", series}, {"xlabel", "maximum spring energy E_cri (mJ)"},
                 {"ylabel", "mean performance index (1/um)"}});
  // Fig 6.26: the same patch at 0.5 mJ (highly flexible).
  const PatchRun run = run_patch(context, surfaces, "patch_neck_20mm.toml", 0.5e-3);
  compare_statistics(report, published, "6.4.2.fig_6_26", "buckling_force", run.evaluation.buckling_force,
                     "Fig 6.26 (E_cri = 0.5 mJ)");
  compare_statistics(report, published, "6.4.2.fig_6_26", "bending_force", run.evaluation.bending_force,
                     "Fig 6.26 (E_cri = 0.5 mJ)");
  render(context, report, surfaces, run, "fig_6_26_flexible_20mm",
         "Fig 6.26: the 20 x 20 mm flexible patch at E_cri = 0.5 mJ on the neck, coloured by buckling force, bending "
         "force and performance index.");
}

void skull(const RunContext& context, SectionReport& report, Surfaces& surfaces, const SectionProgress& progress) {
  const PublishedValues& published = *context.published;
  for (const auto& [example, key, name] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"patch_skull.toml", "skull_10mm", "fig_6_27_skull_10mm"},
           {"patch_skull_20mm.toml", "skull_20mm", "fig_6_27_skull_20mm"}}) {
    context.check_interrupt();
    // The index over the energy range of §6.4.3 (0.005 to 0.05 mJ): the text reports it constant.
    const int points = context.quick ? 2 : 5;
    double lowest = INFINITY, highest = -INFINITY;
    for (int i = 0; i < points; ++i) {
      const double energy = 0.005e-3 + (0.05e-3 - 0.005e-3) * i / (points - 1);
      const PatchRun r = run_patch(context, surfaces, example, energy);
      lowest = std::min(lowest, r.evaluation.performance_index.mean * kMicro);
      highest = std::max(highest, r.evaluation.performance_index.mean * kMicro);
    }
    const PatchRun run = run_patch(context, surfaces, example);
    report.input(case_text(run) + fmt::format("; mean index over E_cri = 0.005 .. 0.05 mJ: {:.6g} .. {:.6g} 1/um",
                                              lowest, highest));
    report.compare(published.at(fmt::format("6.4.3.{}.performance_index_mean", key)),
                   run.evaluation.performance_index.mean * kMicro, fmt::format("§6.4.3 {}: mean performance index", key),
                   "1/um");
    if (key == "skull_20mm") {
      compare_statistics(report, published, "6.4.3.skull", "buckling_force", run.evaluation.buckling_force,
                         "Fig 6.27 skull, 20 x 20 mm");
      compare_statistics(report, published, "6.4.3.skull", "bending_force", run.evaluation.bending_force,
                         "Fig 6.27 skull, 20 x 20 mm");
      const nlohmann::json& s = run.summary;
      report.compare(published.at("6.4.3.critical_buckling_load"), s.value("critical_buckling_load_N", 0.0),
                     "§6.4.3: critical buckling load of the 70/300/1000 um SU-8 cone");
      if (s.contains("critical_bending_load_N") && s["critical_bending_load_N"].is_number()) {
        report.compare(published.at("6.4.3.critical_bending_load"), s["critical_bending_load_N"].get<double>(),
                       "§6.4.3: critical bending load of the cone");
      }
    }
    render(context, report, surfaces, run, name,
           fmt::format("Fig 6.27: the {} flexible patch of 100 conic SU-8 needles (70/300/1000 um) on the skull, "
                       "coloured by buckling force, bending force and performance index.",
                       key == "skull_10mm" ? "10 x 10 mm" : "20 x 20 mm"));
    progress(key == "skull_10mm" ? 0.85 : 1.0, "Fig 6.27");
  }
}

}  // namespace

std::vector<std::filesystem::path> section_6_4_mesh_files(const RunContext& context) {
  std::vector<std::filesystem::path> meshes;
  for (const std::string& example : patch_examples()) {
    const std::filesystem::path mesh = read_case(context, example).mesh;
    if (std::find(meshes.begin(), meshes.end(), mesh) == meshes.end()) meshes.push_back(mesh);
  }
  return meshes;
}

SectionReport section_6_4(const RunContext& context, const SectionProgress& progress) {
  SectionReport report("6.4", "§6.4 Rigid and flexible microneedle patches on skin and skull");
  force_checks(context, report);
  Surfaces surfaces;
  progress(0.05, "loading the surfaces");
  neck_rigid_vs_flexible(context, report, surfaces, progress);
  context.check_interrupt();
  neck_20mm(context, report, surfaces, progress);
  context.check_interrupt();
  skull(context, report, surfaces, progress);
  report.deviation("The body meshes are not the dissertation's (a 79,092-triangle neck and a 92,284-triangle skull, "
                   "not published): needlekit uses the Visible Human Male skin and a CC-BY skull, so the angles under "
                   "the patches and every force that depends on them differ; the forces that F(A) and theta "
                   "determine are checked exactly above.");
  report.deviation("The dissertation's performance index values (its \"MPI\") of §6.4 (0.0289, 0.0291, 0.1184, ...) come from the fitting "
                   "simulation with a normalisation it does not document; needlekit reports Eq 5.9 in 1/um.");
  progress(1, "done");
  return report;
}

}  // namespace needlekit::cli::reproduce
