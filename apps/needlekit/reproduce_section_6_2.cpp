// §6.2 of `needlekit reproduce`: force-depth curves of the sharp bevel, blunt bevel and cylinder in silicone rubber
// (pre-puncture by the FE indentation, post-puncture by the distributed-load model), the puncture points against the
// experiments, the four-needle array of Fig 6.3 and soft vs layered tissue (Fig 6.4).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/complete_insertion.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/indentation_view.hpp"
#include "needlekit/io/insertion_case.hpp"
#include "needlekit/io/insertion_output.hpp"
#include "needlekit/core/errors.hpp"
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {
namespace {

constexpr double kMicro = 1e-6;

// One FE indentation of a case file, with what the figures need from its last converged step.
struct FeRun {
  std::string example;
  insertion::IndentationCase input;
  insertion::IndentationResult result;
  nlohmann::json surface_rows = nlohmann::json::array();  // top-surface nodes at the final depth: x_um, y_um, uz_um, u_um
  nlohmann::json top_rows = nlohmann::json::array();      // elements under the surface: x_um, y_um, von_mises_kPa
  nlohmann::json view;                                     // the 3D view of every load step (io/indentation_view.hpp)
};

// What a run keeps of its final state for the figures.
enum class Capture { Nothing, SurfaceDisplacement, TopStress };

// The resolution of the puncture runs. Full run: the examples' meshes with the element size at the tip at least
// 20 um and at most 20 load steps (the examples' 10 um / 30 steps take about an hour on a 2-core machine). --quick:
// coarser meshes and fewer load steps (the puncture search keeps at least 8 steps).
void set_resolution(insertion::IndentationCase& c, bool quick) {
  if (quick) {
    c.block.size_at_site = std::max(2 * c.block.size_at_site, 30e-6);
    c.block.size_far = std::max(c.block.size_far, 600e-6);
    c.steps = std::max(8, c.steps / 3);
  } else {
    c.block.size_at_site = std::max(c.block.size_at_site, 20e-6);
    c.steps = std::min(c.steps, 20);
  }
}

std::string case_text(const FeRun& run) {
  const insertion::IndentationCase& c = run.input;
  std::string layers;
  for (const mesh::TissueLayer& layer : c.block.layers) {
    layers += fmt::format("{}{} ({:g} um, E = {:g} MPa, nu = {:g})", layers.empty() ? "" : ", ", layer.name,
                          layer.thickness / kMicro, layer.youngs_modulus * 1e-6, layer.poisson_ratio);
  }
  return fmt::format("examples/{}: {} needle(s), block {:g} x {:g} um: {}; mesh {:g} um at the tip, {:g} um far "
                     "({} tetrahedra, {} nodes); {} steps to {:g} um; {} law, {}, {} contact{}",
                     run.example, c.needles.size(), c.block.width / kMicro, c.block.length / kMicro, layers,
                     c.block.size_at_site / kMicro, c.block.size_far / kMicro, run.result.elements, run.result.nodes,
                     c.steps, c.depth / kMicro, fem::to_string(c.solver.law),
                     run.result.nodal_average_elements > 0
                         ? fmt::format("volume averaged at the nodes on {} tetrahedra (locking-free, Bonet & Burton "
                                       "1998)",
                                       run.result.nodal_average_elements)
                         : std::string("volume per element"),
                     fem::to_string(c.solver.contact), c.puncture.critical_pressure
                         ? fmt::format("; puncture at P_c = {:g} MPa", *c.puncture.critical_pressure * 1e-6)
                         : "");
}

FeRun run_fe(const RunContext& context, const std::string& example, insertion::IndentationCase input,
             bool stop_at_puncture, Capture capture, const std::function<void(double)>& progress) {
  FeRun run;
  run.example = example;
  run.input = std::move(input);
  run.input.stop_at_puncture = stop_at_puncture;
  insertion::IndentationOptions options;
  options.progress = [&](const insertion::IndentationProgress& p) {
    context.check_interrupt();
    progress(p.fraction);
  };
  const double cut = 0.75 * run.input.block.size_at_site;
  io::IndentationView view(run.input);
  options.on_mesh = [&](const mesh::TetMesh& tissue) { view.set_mesh(tissue); };
  // The final state only (the last load step reaches the case's depth).
  options.on_step = [&](const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
    context.check_interrupt();
    view.add_step(step, solver);
    if (capture == Capture::Nothing || step.depth < run.input.depth * (1 - 1e-9)) return;
    const auto& nodes = solver.nodes();
    if (capture == Capture::SurfaceDisplacement) {
      const auto& u = solver.displacement();
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (std::abs(nodes[i].z()) > 1e-9) continue;
        run.surface_rows.push_back({nodes[i].x() / kMicro, nodes[i].y() / kMicro, u[i].z() / kMicro, u[i].norm() / kMicro});
      }
      return;
    }
    const fem::ElementFields fields = solver.element_fields();
    const auto& elements = solver.elements();
    for (std::size_t e = 0; e < elements.size(); ++e) {
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k) centroid += nodes[elements[e][k]] / 4;
      if (centroid.z() > -cut) {
        run.top_rows.push_back({centroid.x() / kMicro, centroid.y() / kMicro, fields.von_mises_stress[e] * 1e-3});
      }
    }
  };
  run.result = insertion::run_indentation(run.input, options);
  if (run.result.status == insertion::IndentationStatus::SolverFailed && run.result.steps.empty()) {
    throw std::runtime_error(fmt::format("{}: {}", example, run.result.reason));
  }
  run.view = view.json();
  return run;
}

std::string steps_csv(const insertion::IndentationResult& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const insertion::IndentationStep& s : result.steps) {
    rows.push_back({s.depth / kMicro, s.force, s.contact_pressure * 1e-6, s.max_contact_pressure * 1e-6,
                    s.contact_area * 1e12, s.strain_energy, s.external_work, s.newton_iterations});
  }
  return csv_text({"depth_um", "force_N", "mean_contact_pressure_MPa", "max_contact_pressure_MPa", "contact_area_um2",
                   "strain_energy_J", "external_work_J", "newton_iterations"},
                  rows);
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (x[i] >= at && x[i] > x[i - 1]) return y[i - 1] + (y[i] - y[i - 1]) * (at - x[i - 1]) / (x[i] - x[i - 1]);
  }
  return std::nan("");
}

// A figure case of Figs 6.3/6.4 (no puncture criterion): --quick uses 2 load steps, coarser meshes and, for the
// single needle, a 1.5 mm block (the 20 um stratum corneum caps the element size, so the block's area sets the cost).
FeRun run_figure_case(const RunContext& context, const std::string& example, Capture capture,
                      const std::function<void(double)>& progress) {
  insertion::IndentationCase input = io::read_indentation_case(context.example(example));
  if (context.quick) {
    input.block.size_at_site = std::max(3 * input.block.size_at_site, 60e-6);
    input.block.size_far = std::max(input.block.size_far, 600e-6);
    input.steps = 2;
    if (input.needles.size() == 1) input.block.width = input.block.length = 1500e-6;
  } else {
    input.steps = std::min(input.steps, 5);  // no puncture search: the final state is what the figure shows
  }
  return run_fe(context, example, std::move(input), false, capture, progress);
}

struct PhantomNeedle {
  const char* key;
  const char* label;
  const char* example;  // an insertion case: the indentation case plus [post_puncture]
};

// What the three phantom needles add to the section's figures and table.
struct PhantomFigures {
  nlohmann::json complete_series = nlohmann::json::array(), pre_series = nlohmann::json::array();
  nlohmann::json markers = nlohmann::json::array(), pre_markers = nlohmann::json::array();
  nlohmann::json summary = nlohmann::json::array();
  int earlier_than_experiment = 0;
};

// The complete insertion of one phantom needle: the FE curve to the puncture point, then the post-puncture load of
// the needle's mesh; its 3D view goes into the report.
insertion::CompleteInsertionResult insert_phantom_needle(const RunContext& context, SectionReport& report,
                                                         const PhantomNeedle& n, io::InsertionCase& c,
                                                         const std::function<void(double)>& progress) {
  set_resolution(c.indentation, context.quick);
  c.indentation.stop_at_puncture = true;
  if (context.quick) c.options.curve.cutting_samples = std::min(60, c.options.curve.cutting_samples);
  c.options.indentation.progress = [&](const insertion::IndentationProgress& p) {
    context.check_interrupt();
    progress(p.fraction);
  };
  io::IndentationView view(c.indentation);
  c.options.indentation.on_mesh = [&](const mesh::TetMesh& tissue) { view.set_mesh(tissue); };
  c.options.indentation.on_step = [&](const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
    context.check_interrupt();
    view.add_step(step, solver);
  };
  insertion::CompleteInsertionResult complete = insertion::complete_insertion(c.indentation, c.options);
  if (complete.curve.depth.empty()) throw std::runtime_error(fmt::format("{}: {}", n.example, complete.reason));
  add_view(context, report, fmt::format("6_2_{}", n.key), view.json(),
           fmt::format("{}: the silicone surface pushed in by the needle up to the FE's last step (the puncture point "
                       "or where the FE stopped)",
                       n.label));
  return complete;
}

// The needle's puncture point against the experiment's (the bevels) and against the bound of the dissertation's own
// simulation; the blunt bevel's force at 300 um against Fig 6.6.
void compare_phantom_needle(const RunContext& context, SectionReport& report, const PhantomNeedle& n,
                            const FeRun& run, const insertion::InsertionCurve& curve, PhantomFigures& figures) {
  const PublishedValues& published = *context.published;
  const std::optional<insertion::PuncturePoint>& p = run.result.puncture;
  // How deep the FE got: the case's depth, or less when the solver stopped early (then the report says why).
  const double reached_um = run.result.steps.empty() ? 0.0 : run.result.steps.back().depth / kMicro;
  const bool stopped_early = !p && run.result.status != insertion::IndentationStatus::ReachedDepth;
  if (stopped_early) {
    report.deviation(fmt::format("{}: the FE stopped without puncture at {:.4g} um of the case's {:g} um: {}",
                                 n.label, reached_um, run.input.depth / kMicro, run.result.reason));
  }
  if (p) {
    figures.markers.push_back({{"x", p->depth * 1e3}, {"y", p->force},
                               {"label", fmt::format("needlekit puncture, {}", n.label)}, {"style", "x"}});
    figures.pre_markers.push_back({{"x", p->depth / kMicro}, {"y", p->force},
                                   {"label", fmt::format("puncture, {}", n.label)}, {"style", "x"}});
  }
  const std::string prefix = fmt::format("6.2.{}.", n.key);
  if (n.key != std::string("cylinder")) {
    const PublishedValue& depth = published.at(prefix + "puncture_depth");
    const PublishedValue& force = published.at(prefix + "puncture_force");
    figures.markers.push_back({{"x", depth.value}, {"y", force.value},
                               {"label", fmt::format("experiment, {}", n.label)}, {"style", "o"}});
    if (p) {
      figures.earlier_than_experiment += p->depth * 1e3 < depth.value;
      report.compare(depth, p->depth * 1e3, fmt::format("{}: puncture depth vs experiment", n.label),
                     fmt::format("FE, {} criterion", insertion::to_string(p->criterion)));
      report.compare(force, p->force, fmt::format("{}: puncture force vs experiment", n.label));
    } else {
      report.input(fmt::format("{}: no puncture within the simulated {:.4g} um (experiment: {} mm, {} N)", n.label,
                               reached_um, depth.printed, force.printed));
    }
  }
  // The dissertation's own simulation: bounds on the puncture depth.
  const std::string bound_id = n.key == std::string("sharp_bevel") ? "6.2.sim.sharp_bevel.puncture_depth_below"
                               : n.key == std::string("blunt_bevel") ? "6.2.sim.blunt_bevel.puncture_depth_above"
                                                                      : "6.2.sim.cylinder.puncture_depth_above";
  const PublishedValue& bound = published.at(bound_id);
  const bool below = n.key == std::string("sharp_bevel");
  // Without a puncture the depth is at least the depth reached: the bound holds if that is already beyond it.
  const double depth_um = p ? p->depth / kMicro : reached_um;
  const bool holds = below ? (p && depth_um < bound.value) : depth_um > bound.value;
  report.compare(bound, depth_um,
                 fmt::format("{}: simulated puncture depth ({} {} um in the dissertation's simulation)", n.label,
                             below ? "below" : "beyond", bound.printed),
                 fmt::format("{}; the bound {}",
                             p              ? fmt::format("needlekit punctures at {:.4g} um", depth_um)
                             : stopped_early ? fmt::format("no puncture up to {:.4g} um, where the FE stopped (shown)",
                                                           depth_um)
                                             : "no puncture up to the simulated depth (shown)",
                             holds ? "holds" : stopped_early ? "is not reached" : "does not hold"));
  if (n.key == std::string("blunt_bevel")) {
    const double at_300 = interpolate(curve.depth, curve.force, 300e-6);
    report.compare(published.at("6.2.fig_6_6.blunt_force_at_300um"), at_300,
                   "blunt bevel: insertion force at 300 um (Fig 6.6)", "complete insertion curve at 0.3 mm");
  }
}

void phantom_needles(const RunContext& context, SectionReport& report, const SectionProgress& progress) {
  const std::vector<PhantomNeedle> needles = {{"sharp_bevel", "sharp bevel", "insert_sharp_bevel.toml"},
                                              {"blunt_bevel", "blunt bevel", "insert_blunt_bevel.toml"},
                                              {"cylinder", "cylinder", "insert_cylinder.toml"}};
  PhantomFigures figures;
  for (std::size_t i = 0; i < needles.size(); ++i) {
    const PhantomNeedle& n = needles[i];
    const double lo = 0.5 * i / needles.size(), hi = 0.5 * (i + 1) / needles.size();
    io::InsertionCase c = io::read_insertion_case(context.example(n.example));
    const insertion::CompleteInsertionResult complete =
        insert_phantom_needle(context, report, n, c, [&](double f) { progress(lo + (hi - lo) * f, n.label); });
    const FeRun run{n.example, c.indentation, *complete.indentation, {}, {}, {}};
    const insertion::InsertionCurve& curve = complete.curve;
    report.input(case_text(run) + fmt::format("; post-puncture K = {:g} N/mm^2, S = {:g}, to {:g} um",
                                              complete.stiffness * 1e-6, complete.scale,
                                              c.options.curve.final_depth / kMicro));
    const std::string pre_csv = context.write(fmt::format("section_6_2/{}_pre_puncture.csv", n.key), steps_csv(run.result));
    report.data_file(pre_csv);
    figures.pre_series.push_back(
        {{"csv", pre_csv}, {"x", "depth_um"}, {"y", "force_N"}, {"label", n.label}, {"style", ".-"}});
    const std::string complete_csv =
        context.write(fmt::format("section_6_2/{}_insertion.csv", n.key), io::insertion_curve_csv(curve));
    report.data_file(complete_csv);
    figures.complete_series.push_back(
        {{"csv", complete_csv}, {"x", "depth_um"}, {"y", "force_N"}, {"x_divide_by", 1000.0}, {"label", n.label}});
    compare_phantom_needle(context, report, n, run, curve, figures);
    const std::optional<insertion::PuncturePoint>& p = run.result.puncture;
    figures.summary.push_back(
        {n.label, p ? nlohmann::json(p->depth / kMicro) : nlohmann::json("none"),
         p ? nlohmann::json(p->force) : nlohmann::json("none"), p ? insertion::to_string(p->criterion) : std::string("-"),
         curve.punctures.empty() ? nlohmann::json("-") : nlohmann::json(curve.punctures[0].drop),
         curve.force.empty() ? 0.0 : curve.force.back(), curve.depth.empty() ? 0.0 : curve.depth.back() * 1e3,
         run.result.elements, run.result.total_seconds, insertion::to_string(run.result.status)});
  }
  report.table("§6.2 needles in silicone rubber (E = 0.2 MPa, nu = 0.49): FE puncture points and complete curves",
               {"needle", "puncture_depth_um", "puncture_force_N", "criterion", "relaxation_drop_N",
                "force_at_end_N", "end_depth_mm", "tetrahedra", "fe_seconds", "fe_status"},
               figures.summary, "Post-puncture: K and S of each insert_*.toml example (S = 0.168 of Fig 6.11).");
  report.figure("figures/fig_6_9_insertion_curves.png",
                "Figs 6.9/6.11: complete insertion force of the sharp bevel, blunt bevel and cylinder in silicone rubber "
                "(FE to the puncture point, then the post-puncture model) with the experimental puncture points (circles) "
                "and needlekit's (crosses).",
                {{"kind", "lines"}, {"series", figures.complete_series}, {"markers", figures.markers},
                 {"xlabel", "depth (mm)"}, {"ylabel", "force (N)"}});
  report.figure("figures/fig_6_5_pre_puncture.png",
                "Fig 6.5: pre-puncture FE force-depth curves in silicone rubber; crosses: where the mean pressure under "
                "the tip reaches the critical pressure 0.663 MPa.",
                {{"kind", "lines"}, {"series", figures.pre_series}, {"markers", figures.pre_markers},
                 {"xlabel", "depth (um)"}, {"ylabel", "force (N)"}});
  if (figures.earlier_than_experiment > 0) {
    report.deviation(fmt::format(
        "{} in the FE earlier than in the experiment: the critical-pressure criterion "
        "fires as soon as the mean pressure under the tip reaches P_c, while the phantom in the experiment deforms "
        "further before it cracks; the dissertation's own simulation also punctures earlier than its experiment "
        "(its bounds are compared above).",
        figures.earlier_than_experiment == 2 ? "Both bevels puncture" : "One bevel punctures"));
  }
  report.deviation("K of the post-puncture load is not given by the dissertation: the insert_*.toml examples take the "
                   "phantom's Young's modulus, and S = 0.168 (fitted by the dissertation to the sharp bevel) for every "
                   "needle.");
}

// Fig 6.3: four needles 1600 um apart in layered skin, pushed to 200 um.
void four_needles(const RunContext& context, SectionReport& report, const SectionProgress& progress) {
  const char* example = "indent_fig_6_3_four_needles.toml";
  if (context.quick) {
    report.input(fmt::format("examples/{}: Fig 6.3 runs in the full run only (four needles in a 3 x 3 mm skin block "
                             "whose 20 um stratum corneum needs ~100k tetrahedra: minutes on this machine)",
                             example));
    return;
  }
  insertion::IndentationCase input = io::read_indentation_case(context.example(example));
  input.steps = std::min(input.steps, 5);  // no puncture search: the final state is what the figure shows
  // Surface contact gives no force on sharp needles in this build (the insertion examples use the tip-node rule
  // for the same reason): the tip-node rule of §3.4.
  const bool switched = input.solver.contact == fem::ContactModel::Surface;
  input.solver.contact = fem::ContactModel::TipNodes;
  FeRun run = run_fe(context, example, std::move(input), false, Capture::TopStress,
                     [&](double f) { progress(0.5 + 0.25 * f, "Fig 6.3 four needles"); });
  report.input(case_text(run));
  if (switched) {
    report.deviation("Fig 6.3 uses the dissertation's tip-node contact rule instead of the example's surface contact, "
                     "which gives no force on sharp needles in this build.");
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const insertion::IndentationStep& s : run.result.steps) {
    nlohmann::json row = {s.depth / kMicro, s.force};
    for (double f : s.needle_force) row.push_back(f);
    rows.push_back(row);
  }
  std::vector<std::string> columns = {"depth_um", "total_force_N"};
  for (std::size_t k = 0; k < run.input.needles.size(); ++k) columns.push_back(fmt::format("needle_{}_force_N", k + 1));
  const std::string data = context.write("section_6_2/fig_6_3_four_needles.csv", csv_text(columns, rows));
  const std::string top = context.write("section_6_2/fig_6_3_top_von_mises.csv",
                                        csv_text({"x_um", "y_um", "von_mises_kPa"}, run.top_rows));
  report.data_file(data);
  report.data_file(top);
  add_view(context, report, "6_2_fig_6_3_four_needles", run.view, "Fig 6.3: the skin surface under the four needles");
  nlohmann::json series = nlohmann::json::array();
  series.push_back({{"csv", data}, {"x", "depth_um"}, {"y", "total_force_N"}, {"label", "four needles"}});
  for (std::size_t k = 2; k < columns.size(); ++k) {
    series.push_back({{"csv", data}, {"x", "depth_um"}, {"y", columns[k]}, {"label", fmt::format("needle {}", k - 1)},
                      {"style", "--"}});
  }
  report.figure("figures/fig_6_3_force.png", "Fig 6.3: force on the four-needle array and on each needle.",
                {{"kind", "lines"}, {"series", series}, {"xlabel", "depth (um)"}, {"ylabel", "force (N)"}});
  report.figure("figures/fig_6_3_stress.png",
                fmt::format("Fig 6.3: von Mises stress in the elements just under the skin surface at {:g} um: it "
                            "concentrates at the four sites and at the fixed sides of the block.",
                            run.result.steps.empty() ? 0.0 : run.result.steps.back().depth / kMicro),
                {{"kind", "scatter2d"}, {"csv", top}, {"x", "x_um"}, {"y", "y_um"}, {"value", "von_mises_kPa"},
                 {"xlabel", "x (um)"}, {"ylabel", "y (um)"}, {"colorbar", "von Mises stress (kPa)"}, {"log", true}});
}

// Fig 6.4: the same needle and depth in silicone rubber and in layered skin with a 1 GPa stratum corneum.
void soft_vs_layered(const RunContext& context, SectionReport& report, const SectionProgress& progress) {
  nlohmann::json series = nlohmann::json::array();
  const std::vector<std::pair<const char*, const char*>> cases = {
      {"indent_fig_6_4a_silicone.toml", "(a) silicone rubber, E = 0.2 MPa"},
      {"indent_fig_6_4b_skin.toml", "(b) skin: SC 1 GPa, EP 0.134 MPa, DM 0.08 MPa"}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    FeRun run = run_figure_case(context, cases[i].first, Capture::SurfaceDisplacement,
                                [&](double f) { progress(0.75 + 0.25 * (i + f) / cases.size(), "Fig 6.4"); });
    report.input(case_text(run));
    add_view(context, report, fmt::format("6_2_fig_6_4{}", i == 0 ? "a" : "b"), run.view,
             fmt::format("Fig 6.4{}", cases[i].second));
    nlohmann::json rows = nlohmann::json::array();
    std::vector<std::pair<double, double>> profile;
    for (const nlohmann::json& r : run.surface_rows) {
      profile.emplace_back(std::hypot(r[0].get<double>(), r[1].get<double>()), r[2].get<double>());
    }
    std::sort(profile.begin(), profile.end());
    for (const auto& [radius, uz] : profile) rows.push_back({radius, uz});
    const std::string data = context.write(fmt::format("section_6_2/fig_6_4{}_surface_deflection.csv", i == 0 ? "a" : "b"),
                                           csv_text({"radius_um", "uz_um"}, rows));
    report.data_file(data);
    series.push_back({{"csv", data}, {"x", "radius_um"}, {"y", "uz_um"}, {"label", cases[i].second}, {"style", "."}});
  }
  report.figure("figures/fig_6_4_deflection.png",
                "Fig 6.4: vertical displacement of the tissue surface against the distance from the needle axis at the "
                "final depth: the stiff stratum corneum spreads a shallow deformation over a large area; the soft "
                "phantom deforms deeper in a small area.",
                {{"kind", "lines"}, {"series", series}, {"xlabel", "distance from the axis (um)"},
                 {"ylabel", "surface displacement uz (um)"}});
}

}  // namespace

SectionReport section_6_2(const RunContext& context, const SectionProgress& progress) {
  SectionReport report("6.2", "§6.2 Pre-puncture, puncture and post-puncture insertion forces");
  phantom_needles(context, report, progress);
  context.check_interrupt();
  calibrated_phantom(context, report, progress);
  context.check_interrupt();
  four_needles(context, report, progress);
  context.check_interrupt();
  soft_vs_layered(context, report, progress);
  progress(1, "done");
  return report;
}

}  // namespace needlekit::cli::reproduce
