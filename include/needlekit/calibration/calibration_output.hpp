// Outputs of a calibration: the JSON result and the measured-vs-fitted CSV that scripts/plot_calibration.py plots.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/calibration/calibrate.hpp"

namespace needlekit::calibration {

// {"status", "reason", "iterations", "rms_relative", "model_runs", "warm_started_steps", "seconds", "solver",
//  "parameters": {PATH: {"value", "unit" (SI), "ci95": [lo, hi] or null, "standard_error", "initial", "as_given",
//                        "at_bound"}},
//  "correlation": {"parameters": [PATH...], "matrix": [[...]] (null where not identifiable)}, "warnings": [...],
//  "experiments": [{"name", "kind", "rms_relative", "puncture_depth_um", "puncture_force_N",
//                   "measured_puncture_depth_um", "measured_puncture_force_N", "model_status", "models"}]}.
// Design experiments: the puncture depth is the deformation d before puncture (Eq 4.3).
nlohmann::json calibration_json(const CalibrationProblem& problem, const CalibrationResult& result);

// experiment,series,depth_um,force_N with series = measured | fitted | measured_puncture | fitted_puncture.
std::string calibration_curves_csv(const CalibrationProblem& problem, const CalibrationResult& result);

// A value in the unit the user gave it ("0.2345 MPa"; a bare number for dimensionless keys).
std::string as_given(const ParameterSpec& parameter, double value);

}  // namespace needlekit::calibration
