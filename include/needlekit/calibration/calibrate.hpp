// Fitting case-file parameters to measured force curves and puncture points: bounded nonlinear least squares
// (Levenberg-Marquardt in Ceres Solver, inside src/calibration/calibrate.cpp only) over the weighted relative
// residuals of every experiment (experiment_model.hpp), with a finite-difference Jacobian whose model runs go in
// parallel over experiments and parameters (TBB); then 95 % intervals, correlations and identifiability warnings
// from the Jacobian at the optimum (parameter_statistics.hpp).
//
// The mesh and the post-puncture loads are built once per experiment. The FE runs of a Jacobian warm-start: each
// load step of a perturbed run starts Newton from the centre run's field at the same depth
// (IndentationOptions::warm_start).
#pragma once
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/calibration/calibration_problem.hpp"
#include "needlekit/calibration/experiment_model.hpp"

namespace needlekit::calibration {

enum class CalibrationStatus {
  Converged,     // a convergence test of the solver holds (function, parameter or gradient tolerance)
  NotConverged,  // max_iterations reached; the best point so far is the result
  Failed,        // the model failed at the initial point or the solver gave up; the last good point is kept
  Stopped,       // the progress callback asked to stop (Ctrl-C); the best point so far is the result
};
inline constexpr EnumTable<CalibrationStatus, 4> kCalibrationStatusNames{{
    {CalibrationStatus::Converged, "converged", "a convergence test of the solver holds"},
    {CalibrationStatus::NotConverged, "not-converged", "max_iterations reached; the best point so far is the result"},
    {CalibrationStatus::Failed, "failed",
     "the model failed at the initial point or the solver gave up; the last good point is kept"},
    {CalibrationStatus::Stopped, "stopped", "the progress callback asked to stop; the best point so far is the result"},
}};
std::string_view to_string(CalibrationStatus status);

struct CalibrationProgress {
  int iteration = 0;          // 0: the initial point
  double rms_relative = 0;    // RMS of the weighted relative residuals
  std::vector<double> values; // SI, the current parameters
  int model_runs = 0;         // FE runs so far
  double seconds = 0;
};

struct CalibrationOptions {
  // After every solver iteration (calling thread); returning false stops the fit there (status Stopped).
  std::function<bool(const CalibrationProgress&)> progress;
  // Polled inside the FE runs, at every Newton iteration (from any thread; must be thread-safe): true stops the
  // run at once and the fit after it (status Stopped; the best point so far is kept). The CLI's Ctrl-C, which
  // would otherwise wait for the end of a solver iteration: several FE runs.
  std::function<bool()> stop_requested;
};

struct FittedParameter {
  ParameterSpec spec;
  double value = 0;                                   // SI
  double standard_error = 0;                          // SI; NaN when not identifiable
  std::optional<std::pair<double, double>> ci95;      // SI: the noise's interval widened by discretisation_error
  double discretisation_error = 0;                    // SI, >= 0: estimated FE mesh error (discretisation_error.hpp)
  bool at_bound = false;                              // the optimum lies on a bound (the interval ignores it)
};

struct ExperimentFit {
  std::string name;
  ExperimentKind kind = ExperimentKind::Insertion;
  double rms_relative = 0;
  bool predicted_only = false;                        // all weights 0: run once at the fitted values, not fitted
  Prediction prediction;                              // at the fitted values
  std::vector<double> residuals;
};

struct CalibrationResult {
  CalibrationStatus status = CalibrationStatus::Failed;
  std::string reason;
  int iterations = 0;
  double rms_relative = 0;                            // all experiments
  std::vector<FittedParameter> parameters;
  Eigen::MatrixXd correlation;                        // NaN where not identifiable
  std::vector<std::string> warnings;                  // identifiability, bounds, model notes
  std::vector<ExperimentFit> experiments;
  int model_runs = 0;                                 // FE runs
  int warm_started_steps = 0;                         // FE load steps of the finite differences started warm
  double seconds = 0;
  std::vector<double> values() const;                 // SI, in the order of the parameters
};

// Throws InvalidInput (naming the calibration file and the parameter's key) for a parameter that no experiment
// depends on, and for cases that do not read; numerical failure is a status.
CalibrationResult calibrate(const CalibrationProblem& problem, const CalibrationOptions& options = {});

// The case file of `experiment` with the fitted values written in the units the user gave (6 significant digits).
std::string calibrated_case_text(const CalibrationProblem& problem, std::size_t experiment,
                                 const std::vector<double>& values);

}  // namespace needlekit::calibration
