// The results of `needlekit uncertainty`: one JSON object (units in the key names; NaN, i.e. undefined, as null)
// and the CSV tables written with --out.
//   {"samples", "method", "seed", "evaluations", "status", "reason",
//    "inputs": [{"key", "distribution"}],
//    "probabilities": {EVENT: {"value", "ci95": [lo, hi], "samples_defined"}},
//    "performance_index_per_um": {"mean", "ci95_mean", "sd", "q05", "q50", "q95", "histogram": {"edges", "counts"}},
//    "nominal": {"performance_index_per_um", "status"},
//    "sobol": {"first": {INPUT: S}, "total": {INPUT: ST}, "first_ci95": {INPUT: [lo, hi]}, "total_ci95": {...},
//              "events": {EVENT: {"first": {...}, "total": {...}}}},
//    "one_at_a_time": {INPUT: {"low", "high", "unit", "performance_index_low_per_um", "performance_index_high_per_um"}},
//    "notes": [...]}
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/analysis/design_space.hpp"
#include "needlekit/io/fe_uncertainty_config.hpp"
#include "needlekit/io/patch_uncertainty_config.hpp"
#include "needlekit/io/uncertainty_config.hpp"
#include "needlekit/io/vtu_writer.hpp"
#include "needlekit/uncertainty/robust_design.hpp"

namespace needlekit::io {

nlohmann::json uncertainty_json(const UncertaintyFile& file, const uncertainty::DesignUncertaintyResult& result);

// `optimize` with min_success_probability: optimizer_json of the nominal ranking plus
//   "robust": {"min_success_probability", "status", "reason", "samples", "method", "seed",
//              "design": {candidate, "success_probability", "success_ci95"}, "nominal_optimum": {... the same},
//              "index_cost_per_um", "index_cost_percent", "candidates_checked"}
nlohmann::json robust_design_json(const analysis::DesignSpace& space, const uncertainty::RobustDesignOptions& options,
                                  const uncertainty::RobustDesignResult& result);

// "performance_index_low_per_um,performance_index_high_per_um,count" rows of the index histogram.
std::string index_histogram_csv(const uncertainty::DesignUncertaintyResult& result);
// "output,input,first,first_lo,first_hi,total,total_lo,total_hi" rows (output: performance_index or an event).
std::string sobol_csv(const uncertainty::DesignUncertaintyResult& result);

// A patch case (uncertainty::patch_uncertainty):
//   {"samples", "method", "seed", "evaluations", "status", "reason", "inputs": [{"key", "distribution"}],
//    "probabilities": {"all_succeed" | "at_least_X_percent" | "invalid_sample": {"value", "ci95", "samples_defined"}},
//    "success_fraction": {"mean", "ci95_mean", "sd", "q05", "q50", "q95", "histogram": {"edges", "counts"}},
//    "nominal": {"fit_status", "success_fraction", "needles"},
//    "sobol": {"first", "total", "first_ci95", "total_ci95" (of success_fraction), "events": {"all_succeed": ...}},
//    "needles": [{"index", "i", "j", "position_mm": [x, y, z], "probabilities": {EVENT: {"value", "ci95"}}}],
//    "notes": [...]}
// position_mm is the needle's base in the nominal fit.
nlohmann::json patch_uncertainty_json(const PatchUncertaintyFile& file, const uncertainty::PatchUncertaintyResult& result);
// One row per needle: needle,i,j,x_mm,y_mm,z_mm,u_mm,v_mm (nominal base; rest position in the patch), then
// P_EVENT,P_EVENT_lo,P_EVENT_hi for puncture, buckling_failure, bending_failure, reaches_target, success.
std::string patch_probability_csv(const uncertainty::PatchUncertaintyResult& result);
// The needles' nominal bases as vertices with point fields P_EVENT (and P_success_lo, P_success_hi).
VtuGrid patch_probability_grid(const uncertainty::PatchUncertaintyResult& result);

// An FE case (uncertainty::fe_surrogate):
//   {"samples", "method", "seed", "evaluations" (of the surrogate), "status", "reason", "inputs",
//    "surrogate": {"kind", "terms", "fe_runs", "elements", "design_runs", "validation_runs", "fe_seconds",
//                  "validation_error": {"puncture_depth" | "puncture_force": {"max_relative", "rms_relative"}},
//                  "fit_error": {... the same at the design runs}},
//    "depth_limit_um", "probabilities": {"punctures_before_depth": {"value", "ci95", "samples_defined"}},
//    "puncture_depth_um", "puncture_force_N": {"mean", "ci95_mean", "sd", "q05", "q50", "q95", "histogram"},
//    "nominal": {"puncture_depth_um", "puncture_force_N", "status"}, "sobol" (of the depth, or null), "notes"}
// Empty distributions (status failed) are null.
nlohmann::json fe_uncertainty_json(const FeUncertaintyFile& file, const uncertainty::FeSurrogateResult& result);
// One row per FE run: role (nominal, design, validation), the inputs in MPa, status, puncture_depth_um,
// puncture_force_N, surrogate_depth_um, surrogate_force_N, seconds.
std::string fe_runs_csv(const FeUncertaintyFile& file, const uncertainty::FeSurrogateResult& result);

}  // namespace needlekit::io
