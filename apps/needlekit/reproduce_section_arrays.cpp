// The array section of `needlekit reproduce` (issue 36, beyond the dissertation): the 3 x 3 patch of
// examples/indent_array_3x3.toml pressed into two-layer skin — which needles go in, when, and how deep (the per-needle
// table, the needle map and the plate's force and punctured fraction against its travel) — and the "bed of nails":
// the plate's travel to the first puncture of a 2 x 2 patch of the same needle at four pitches (docs/arrays.md).
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/array_output.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/indentation_view.hpp"
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {
namespace {

constexpr double kMicro = 1e-6;
constexpr const char* kExample = "indent_array_3x3.toml";

// --quick: a coarser mesh under the tips and far away (the puncture of every needle is still resolved by the
// example's steps).
insertion::IndentationCase example_case(const RunContext& context) {
  insertion::IndentationCase c = io::read_indentation_case(context.example(kExample));
  if (context.quick) {
    c.block.size_at_site = std::max(c.block.size_at_site, 45e-6);
    c.block.size_far = std::max(c.block.size_far, 500e-6);
  }
  return c;
}

insertion::IndentationResult run(const RunContext& context, const insertion::IndentationCase& c,
                                 insertion::IndentationOptions options, const std::function<void(double)>& progress) {
  options.progress = [&](const insertion::IndentationProgress& p) {
    context.check_interrupt();
    progress(p.fraction);
  };
  insertion::IndentationResult result = insertion::run_indentation(c, options);
  if (result.steps.empty()) throw std::runtime_error(fmt::format("{}: {}", kExample, result.reason));
  return result;
}

void three_by_three(const RunContext& context, SectionReport& report, const SectionProgress& progress) {
  const insertion::IndentationCase c = example_case(context);
  io::IndentationView view(c);
  insertion::IndentationOptions options;
  options.on_mesh = [&](const mesh::TetMesh& tissue) { view.set_mesh(tissue); };
  options.on_step = [&](const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
    context.check_interrupt();
    view.add_step(step, solver);
  };
  const insertion::IndentationResult result = run(context, c, options, [&](double f) { progress(0.5 * f, "3 x 3"); });
  const nlohmann::json array = io::array_json(c, result);
  report.input(fmt::format("examples/{}: {} x {} cones ({:g} um tips, {:g} um bases, {:g} um long) {:g} um apart on a "
                           "backing plate; block {:g} x {:g} um, {:g} um at the tips ({} tetrahedra); {} steps to "
                           "{:g} um; puncture at P_c = {:g} MPa under each tip",
                           kExample, c.array->rows, c.array->columns, c.geometry->tip_diameter / kMicro,
                           c.geometry->base_diameter / kMicro, c.geometry->length / kMicro, c.array->pitch / kMicro,
                           c.block.width / kMicro, c.block.length / kMicro, c.block.size_at_site / kMicro,
                           result.elements, c.steps, c.depth / kMicro, c.puncture.critical_pressure.value_or(0) * 1e-6));
  const std::string needles = context.write("section_arrays/array_3x3_needles.csv", io::needles_csv(c, result));
  report.data_file(needles);
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t k = 0; k < result.needles.size(); ++k) {
    const insertion::NeedleOutcome& n = result.needles[k];
    rows.push_back({k, n.position.x() / kMicro, n.position.y() / kMicro, n.force.empty() ? 0.0 : n.force.back(),
                    n.puncture_step, n.inserted_depth / kMicro});
  }
  report.table("Every needle at the last step (needle k = row * columns + column, row 0 at the smallest y)",
               {"needle", "x_um", "y_um", "force_N", "puncture_step", "inserted_depth_um"}, rows,
               "puncture_step 0: not punctured. The corner needles, with the fewest neighbours drawing the surface "
               "down, go in first; the centre needle last.");
  report.figure("figures/array_3x3_needle_map.png",
                "The needle map: each needle at its place, coloured by how deep it went in beyond its puncture.",
                {{"kind", "scatter2d"}, {"csv", needles}, {"x", "x_um"}, {"y", "y_um"}, {"value", "inserted_depth_um"},
                 {"xlabel", "x (um)"}, {"ylabel", "y (um)"}, {"colorbar", "inserted depth (um)"}});
  nlohmann::json plate = nlohmann::json::array();
  for (std::size_t s = 0; s < result.steps.size(); ++s) {
    plate.push_back({array["plate_travel_um"][s], result.steps[s].force, array["punctured_fraction"][s]});
  }
  const std::string plate_csv = context.write("section_arrays/array_3x3_plate.csv",
                                              csv_text({"plate_travel_um", "force_N", "punctured_fraction"}, plate));
  report.data_file(plate_csv);
  report.figure("figures/array_3x3_plate.png",
                fmt::format("The backing plate's force against its travel; {:.0f} % of the needles punctured at the "
                            "end, mean inserted depth {:.1f} um ({:.1f} % of the needle's length).",
                            100 * array["punctured_fraction"].back().get<double>(),
                            array["mean_inserted_depth_um"].get<double>(),
                            100 * array["mean_penetrated_fraction"].get<double>()),
                {{"kind", "lines"},
                 {"series", {{{"csv", plate_csv}, {"x", "plate_travel_um"}, {"y", "force_N"}, {"label", "plate"}}}},
                 {"xlabel", "plate travel (um)"},
                 {"ylabel", "force (N)"}});
  add_view(context, report, "arrays_3x3", view.json(), "The 3 x 3 patch pressed into the skin, step by step");
}

// The bed of nails: a 2 x 2 patch (its quarter model) of the same needle at four pitches.
void pitch_sweep(const RunContext& context, SectionReport& report, const SectionProgress& progress) {
  const std::vector<double> pitches = {1200e-6, 900e-6, 600e-6, 300e-6};
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t i = 0; i < pitches.size(); ++i) {
    insertion::IndentationCase c = example_case(context);
    insertion::NeedleArray array = *c.array;
    array.rows = array.columns = 2;
    array.pitch = pitches[i];
    array.symmetry = insertion::ArraySymmetry::Quarter;
    insertion::set_array(c, array, c.needles.front().tip_height);
    c.stop_at_puncture = false;
    const insertion::IndentationResult result =
        run(context, c, {}, [&](double f) { progress(0.5 + 0.5 * (i + f) / pitches.size(), "pitch sweep"); });
    const std::optional<double> travel = result.array ? result.array->first_puncture_travel : std::nullopt;
    rows.push_back({pitches[i] / kMicro, travel ? nlohmann::json(*travel / kMicro) : nlohmann::json(nullptr),
                    result.array ? result.array->punctured_fraction.back() : 0.0});
  }
  report.table("The plate's travel to the first puncture of a 2 x 2 patch (quarter model) against the pitch",
               {"pitch_um", "first_puncture_travel_um", "punctured_fraction_at_end"}, rows,
               "The closer the needles, the more the skin tents between them and the further the plate must travel "
               "before a tip reaches the critical pressure (Olatunji et al. 2013 measured the force per needle rising "
               "as the spacing fell).");
  report.deviation("Arrays are beyond the dissertation (which runs Fig 6.3's four needles only); the model leaves out "
                   "the skin's pre-tension, friction along the shafts and the needles' deflection (docs/arrays.md).");
}

}  // namespace

SectionReport section_arrays(const RunContext& context, const SectionProgress& progress) {
  SectionReport report("arrays", "Beyond the dissertation: a microneedle patch pressed into skin");
  three_by_three(context, report, progress);
  context.check_interrupt();
  pitch_sweep(context, report, progress);
  progress(1, "done");
  return report;
}

}  // namespace needlekit::cli::reproduce
