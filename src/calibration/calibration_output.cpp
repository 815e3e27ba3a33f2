#include "needlekit/calibration/calibration_output.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/units.hpp"

namespace needlekit::calibration {
namespace {

nlohmann::json number_or_null(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); }

nlohmann::json optional_um(const std::optional<double>& metres) {
  return metres ? nlohmann::json(*metres * 1e6) : nlohmann::json(nullptr);
}

}  // namespace

std::string as_given(const ParameterSpec& p, double value) {
  if (p.dimension == units::Dimension::Dimensionless) return fmt::format("{:.6g}", value);
  return units::format(value, p.unit.empty() ? units::si_symbol(p.dimension) : p.unit);
}

nlohmann::json calibration_json(const CalibrationProblem& problem, const CalibrationResult& r) {
  nlohmann::json parameters = nlohmann::json::object();
  std::vector<std::string> names;
  for (const FittedParameter& p : r.parameters) {
    names.push_back(p.spec.path);
    parameters[p.spec.path] = {
        {"value", p.value},
        {"unit", units::si_symbol(p.spec.dimension)},
        {"ci95", p.ci95 ? nlohmann::json::array({p.ci95->first, p.ci95->second}) : nlohmann::json(nullptr)},
        {"standard_error", number_or_null(p.standard_error)},
        {"discretisation_error", p.discretisation_error},
        {"initial", p.spec.initial},
        {"as_given", as_given(p.spec, p.value)},
        {"at_bound", p.at_bound},
    };
  }
  nlohmann::json matrix = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.correlation.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < r.correlation.cols(); ++j) row.push_back(number_or_null(r.correlation(i, j)));
    matrix.push_back(row);
  }
  nlohmann::json experiments = nlohmann::json::array();
  for (std::size_t e = 0; e < r.experiments.size(); ++e) {
    const ExperimentFit& fit = r.experiments[e];
    const ExperimentSpec& spec = problem.experiments[e];
    const auto& puncture = fit.prediction.puncture;
    experiments.push_back({
        {"name", fit.name},
        {"kind", to_string(fit.kind)},
        {"case", spec.case_path.string()},
        {"rms_relative", fit.predicted_only ? nlohmann::json(nullptr) : nlohmann::json(fit.rms_relative)},
        {"predicted_only", fit.predicted_only},
        {"puncture_depth_um", puncture ? nlohmann::json(puncture->depth * 1e6) : nlohmann::json(nullptr)},
        {"puncture_force_N", puncture ? nlohmann::json(puncture->force) : nlohmann::json(nullptr)},
        {"measured_puncture_depth_um", optional_um(spec.puncture.depth)},
        {"measured_puncture_force_N", spec.puncture.force ? nlohmann::json(*spec.puncture.force) : nlohmann::json(nullptr)},
        {"model_status", fit.prediction.status},
    });
  }
  return {
      {"name", problem.name},
      {"status", to_string(r.status)},
      {"reason", r.reason},
      {"iterations", r.iterations},
      {"rms_relative", r.rms_relative},
      {"model_runs", r.model_runs},
      {"warm_started_steps", r.warm_started_steps},
      {"seconds", r.seconds},
      {"solver", "Ceres Solver, Levenberg-Marquardt with bounds, finite-difference Jacobian"},
      {"parameters", parameters},
      {"correlation", {{"parameters", names}, {"matrix", matrix}}},
      {"warnings", r.warnings},
      {"experiments", experiments},
  };
}

std::string calibration_curves_csv(const CalibrationProblem& problem, const CalibrationResult& r) {
  std::string csv = "experiment,series,depth_um,force_N\n";
  const auto row = [&](const std::string& name, std::string_view series, double depth, double force) {
    csv += fmt::format("{},{},{:.9g},{:.9g}\n", name, series, depth * 1e6, force);
  };
  for (std::size_t e = 0; e < r.experiments.size(); ++e) {
    const ExperimentSpec& spec = problem.experiments[e];
    const ExperimentFit& fit = r.experiments[e];
    if (spec.measured)
      for (std::size_t i = 0; i < spec.measured->depth.size(); ++i)
        row(fit.name, "measured", spec.measured->depth[i], spec.measured->force[i]);
    for (std::size_t i = 0; i < fit.prediction.curve.depth.size(); ++i)
      row(fit.name, "fitted", fit.prediction.curve.depth[i], fit.prediction.curve.force[i]);
    if (spec.puncture.depth && spec.puncture.force)
      row(fit.name, "measured_puncture", *spec.puncture.depth, *spec.puncture.force);
    if (fit.prediction.puncture)
      row(fit.name, "fitted_puncture", fit.prediction.puncture->depth, fit.prediction.puncture->force);
  }
  return csv;
}

}  // namespace needlekit::calibration
