#include "needlekit/io/complete_insertion_output.hpp"

#include "needlekit/io/indentation_output.hpp"
#include "needlekit/io/insertion_output.hpp"
#include "needlekit/io/parameter_json.hpp"

namespace needlekit::io {

nlohmann::json complete_insertion_json(const InsertionCase& insertion_case,
                                       const insertion::CompleteInsertionResult& result,
                                       const std::vector<std::string>& notes) {
  const insertion::IndentationCase& indentation_case = insertion_case.indentation;
  const insertion::CompleteInsertionOptions& options = insertion_case.options;
  nlohmann::json json = insertion_curve_json(result.curve);
  json["status"] = insertion::to_string(result.status);
  json["reason"] = result.reason;
  json["name"] = indentation_case.name;
  json["needles"] = indentation_case.needles.size();
  // Each needle's own curve (an array's per-needle post-puncture force): where it stands, its force at every sample
  // of depth_um, and the array's displacement when it punctured.
  nlohmann::json needle_curves = nlohmann::json::array();
  for (std::size_t i = 0; i < result.curve.needle_force.size() && i < indentation_case.needles.size(); ++i) {
    const Eigen::Vector2d& at = indentation_case.needles[i].position;
    nlohmann::json curve = {{"needle", i + 1}, {"x_um", at.x() * 1e6}, {"y_um", at.y() * 1e6},
                            {"force_N", result.curve.needle_force[i]}, {"puncture_displacement_um", nullptr}};
    for (const insertion::PunctureEvent& event : result.curve.punctures) {
      if (event.needle == static_cast<int>(i)) curve["puncture_displacement_um"] = event.displacement * 1e6;
    }
    needle_curves.push_back(std::move(curve));
  }
  json["needle_curves"] = needle_curves;
  json["stiffness_N_per_mm2"] = result.stiffness * 1e-6;
  json["scale"] = result.scale;
  json["scale_source"] = result.fit ? "fitted" : "case";
  json["case_scale"] = options.model.scale;
  json["final_depth_um"] = options.curve.final_depth * 1e6;
  json["pre_puncture_source"] = result.indentation ? "fe" : "csv";
  json["complete"] = result.status != insertion::CompleteInsertionStatus::SolverFailed;
  json["notes"] = notes;
  nlohmann::json inputs = indentation_inputs_json(indentation_case);
  for_each_post_puncture_table(options, [&inputs](const auto& table, const auto& values) {
    add_parameters_json(table, values, inputs);
  });
  json["inputs"] = inputs;
  if (const std::optional<insertion::IndentationResult>& fe = result.indentation) {
    json["fe"] = {{"status", insertion::to_string(fe->status)}, {"reason", fe->reason}, {"elements", fe->elements},
                  {"nodes", fe->nodes}, {"total_seconds", fe->total_seconds},
                  {"models", fe_models_json(indentation_case)}};
  }
  const auto& loads = result.loads;
  const auto& classes = loads.classification;
  json["classification"] = {{"alpha", classes.alpha.size()},   {"beta", classes.beta.size()},
                            {"side", classes.side},            {"back", classes.back},
                            {"channel", classes.channel},      {"occluded", classes.occluded},
                            {"alpha_area_um2", classes.alpha_area * 1e12}, {"beta_area_um2", classes.beta_area * 1e12},
                            {"loaded_subtriangles", loads.triangles.size()},
                            {"reference_radius_um", loads.reference_radius * 1e6}};
  json["fit"] = nullptr;
  if (const std::optional<insertion::PostPunctureFit>& fit = result.fit) {
    json["fit"] = {{"scale", fit->scale}, {"stiffness_N_per_mm2", fit->stiffness * 1e-6},
                   {"rms_error_N", fit->rms_error}, {"relative_rms", fit->relative_rms}, {"samples", fit->samples}};
  }
  return json;
}

}  // namespace needlekit::io
