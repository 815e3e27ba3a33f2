// The uncertainty section of `needlekit reproduce` (issue 15, beyond the dissertation): the SU-8 cone of
// examples/uncertainty_cone_su8.toml on variable skin (event probabilities, the spread of the performance index,
// Sobol' indices beside the one-at-a-time swings of Fig 6.18) and the robust design of
// examples/optimize_robust_cone_su8.toml (the best design with P(success) >= 0.99 and its index cost), and the
// per-needle probability map of the neck patch of examples/uncertainty_patch_neck.toml (uncertain placement and skin).
#include <fmt/format.h>

#include <string>

#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/patch_uncertainty_config.hpp"
#include "needlekit/io/uncertainty_config.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "needlekit/uncertainty/robust_design.hpp"
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {
namespace {

nlohmann::json value_or_null(const nlohmann::json& value) { return value.is_null() ? nlohmann::json(nullptr) : value; }

// {event, probability, ci95_lo, ci95_hi} rows of a study's "probabilities".
nlohmann::json probability_rows(const nlohmann::json& json) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [event, p] : json["probabilities"].items()) {
    rows.push_back({event, value_or_null(p["value"]), value_or_null(p["ci95"][0]), value_or_null(p["ci95"][1])});
  }
  return rows;
}

void design_study(const RunContext& context, SectionReport& report) {
  io::UncertaintyFile file = io::read_uncertainty_file(context.example("uncertainty_cone_su8.toml"));
  if (context.quick) file.sampling.samples = 1024;
  uncertainty::DesignUncertaintyOptions options;
  options.sampling = file.sampling;
  const uncertainty::DesignUncertaintyResult r =
      uncertainty::design_uncertainty(file.design, file.inputs, file.correlations, options);
  const nlohmann::json json = io::uncertainty_json(file, r);
  report.input(fmt::format("examples/uncertainty_cone_su8.toml: {} {} samples, seed {}", json["samples"].get<std::size_t>(),
                           json["method"].get<std::string>(), json["seed"].get<std::uint64_t>()));
  for (const auto& input : json["inputs"]) {
    report.input(fmt::format("{}: {}", input["key"].get<std::string>(), input["distribution"].get<std::string>()));
  }
  const nlohmann::json rows = probability_rows(json);
  report.table("Probability of each event (SU-8 cone, 10 x 10 on 1 cm, skin with uncertain alpha and tau, angle "
               "0-20 deg)",
               {"event", "probability", "ci95_lo", "ci95_hi"}, rows);

  const auto& index = json["performance_index_per_um"];
  nlohmann::json categories = nlohmann::json::array(), counts = nlohmann::json::array();
  const auto& edges = index["histogram"]["edges"];
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    categories.push_back(fmt::format("{:.3g}", 0.5 * (edges[b].get<double>() + edges[b + 1].get<double>())));
    counts.push_back(index["histogram"]["counts"][b]);
  }
  report.figure("figures/uq_index_histogram.png",
                fmt::format("Distribution of the performance index (1/um) over the samples: mean {:.4g}, q05 {:.4g}, "
                            "q50 {:.4g}, q95 {:.4g} (nominal {:.4g}). The bar at 0 is the failed insertions.",
                            index["mean"].get<double>(), index["q05"].get<double>(), index["q50"].get<double>(),
                            index["q95"].get<double>(), json["nominal"]["performance_index_per_um"].get<double>()),
                {{"kind", "bars"},
                 {"categories", categories},
                 {"series", {{{"label", "samples"}, {"values", counts}}}},
                 {"ylabel", "samples per bin"}});

  nlohmann::json keys = nlohmann::json::array(), first = nlohmann::json::array(), total = nlohmann::json::array(),
                 success_total = nlohmann::json::array(), oat_rows = nlohmann::json::array();
  for (const auto& input : json["inputs"]) {
    const std::string key = input["key"].get<std::string>();
    keys.push_back(key);
    first.push_back(value_or_null(json["sobol"]["first"][key]));
    total.push_back(value_or_null(json["sobol"]["total"][key]));
    success_total.push_back(value_or_null(json["sobol"]["events"]["success"]["total"][key]));
    const auto& o = json["one_at_a_time"][key];
    oat_rows.push_back({key, o["low"], o["high"], o["unit"], o["performance_index_low_per_um"],
                        o["performance_index_high_per_um"], value_or_null(json["sobol"]["first"][key]),
                        value_or_null(json["sobol"]["total"][key])});
  }
  report.figure("figures/uq_sobol_indices.png",
                "Sobol' indices of the performance index (first order and total, Saltelli/Jansen) and the total "
                "index of the success indicator, per uncertain input.",
                {{"kind", "bars"},
                 {"categories", keys},
                 {"series", {{{"label", "index: first order"}, {"values", first}},
                             {{"label", "index: total"}, {"values", total}},
                             {{"label", "success: total"}, {"values", success_total}}}},
                 {"ylabel", "Sobol' index"}});
  report.table("One at a time (as Fig 6.18) beside the Sobol' indices: the index with one input at its 5 % and 95 % "
               "quantiles, the others nominal",
               {"input", "low", "high", "unit", "PI_low_per_um", "PI_high_per_um", "S_i", "ST_i"}, oat_rows,
               "An input can move the index a lot through failures that one-at-a-time swings never meet: the angle "
               "leaves the nominal index unchanged at both quantiles, yet its total index is large.");
  report.data_file(context.write("uncertainty/performance_index_histogram.csv", io::index_histogram_csv(r)));
  report.data_file(context.write("uncertainty/sobol_indices.csv", io::sobol_csv(r)));
  report.data_file(context.write("uncertainty/uncertainty.json", io::json_text(json)));
}

void robust_design(const RunContext& context, SectionReport& report) {
  const io::SpaceFile file = io::read_space_file(context.example("optimize_robust_cone_su8.toml"));
  uncertainty::RobustDesignOptions options;
  options.min_success_probability = file.robust->min_success_probability;
  options.sampling = file.robust->sampling;
  const uncertainty::RobustDesignResult r =
      uncertainty::robust_design(file.space, file.robust->inputs, file.robust->correlations, options);
  const nlohmann::json robust = io::robust_design_json(file.space, options, r)["robust"];
  report.input(fmt::format("examples/optimize_robust_cone_su8.toml: P(success) >= {:g}, {} samples per candidate",
                           r.min_success_probability, options.sampling.samples));
  nlohmann::json rows = nlohmann::json::array();
  for (const char* which : {"nominal_optimum", "design"}) {
    const auto& d = robust[which];
    if (d.is_null()) continue;
    rows.push_back({which, d["needles_per_row"], d["tip_diameter_um"], d["base_diameter_um"], d["width_um"],
                    d["length_um"], d["performance_index_per_um"], d["success_probability"]});
  }
  report.table(fmt::format("Robust design: the best nominal design with P(success) >= {:g} ({}; {} candidates "
                           "checked, index cost {})",
                           r.min_success_probability, robust["status"].get<std::string>(),
                           robust["candidates_checked"].get<std::size_t>(),
                           robust["index_cost_percent"].is_null()
                               ? std::string("-")
                               : fmt::format("{:.3g} %", robust["index_cost_percent"].get<double>())),
               {"design", "n", "D1_um", "D2_um", "w_um", "L_um", "PI_per_um", "P_success"}, rows);
}

void patch_map(const RunContext& context, SectionReport& report) {
  io::PatchUncertaintyFile file = io::read_patch_uncertainty_file(context.example("uncertainty_patch_neck.toml"));
  if (!context.meshes.empty()) file.patch.mesh = context.meshes / file.patch.mesh.filename();
  if (context.quick) file.sampling.samples = 256;
  const geometry::BodySurface body = geometry::read_body_surface(file.patch.mesh, file.patch.mesh_unit);
  uncertainty::PatchUncertaintyOptions options;
  options.sampling = file.sampling;
  const uncertainty::PatchUncertaintyResult r = uncertainty::patch_uncertainty(
      {&body.surface, file.patch.design, io::fit_and_evaluate_options(file.patch)}, file.inputs, file.correlations,
      options);
  const nlohmann::json json = io::patch_uncertainty_json(file, r);
  report.input(fmt::format("examples/uncertainty_patch_neck.toml: {} {} samples, seed {}", r.propagation.samples,
                           json["method"].get<std::string>(), json["seed"].get<std::uint64_t>()));
  const nlohmann::json rows = probability_rows(json);
  report.table("The flexible 10 x 10 neck patch of §6.4.1 placed within 3 mm of its vertex, turned by ~10 deg, on "
               "skin with uncertain alpha and tau: patch-level probabilities",
               {"event", "probability", "ci95_lo", "ci95_hi"}, rows);
  const std::string csv = context.write("uncertainty/needle_probabilities.csv", io::patch_probability_csv(r));
  report.data_file(csv);
  report.figure("figures/uq_patch_map.png",
                fmt::format("P(success) of each needle over the patch (rest positions u, v): the mean fraction of "
                            "needles that succeed is {:.3g}; the edge columns fail most, where the patch leaves the "
                            "neck's flat part.",
                            json["success_fraction"]["mean"].get<double>()),
                {{"kind", "scatter2d"}, {"csv", csv}, {"x", "u_mm"}, {"y", "v_mm"}, {"value", "P_success"},
                 {"cmap", "RdYlGn"}, {"size", 90}, {"xlabel", "u (mm)"}, {"ylabel", "v (mm)"},
                 {"colorbar", "P(success)"}});
}

}  // namespace

SectionReport section_uncertainty(const RunContext& context, const SectionProgress& progress) {
  SectionReport report("uq", "Beyond Chapter 6: the probability that a design works on variable skin");
  progress(0, "uncertainty study");
  design_study(context, report);
  context.check_interrupt();
  progress(0.5, "robust design");
  robust_design(context, report);
  context.check_interrupt();
  progress(0.7, "patch probability map");
  patch_map(context, report);
  progress(1, "done");
  return report;
}

}  // namespace needlekit::cli::reproduce
