#include "needlekit/calibration/calibrate.hpp"

#include <ceres/ceres.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <functional>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <mutex>

#include "needlekit/calibration/calibration_solver_parameters.hpp"
#include "needlekit/calibration/case_parameters.hpp"
#include "needlekit/calibration/discretisation_error.hpp"
#include "needlekit/calibration/parameter_statistics.hpp"
#include "needlekit/core/errors.hpp"

namespace needlekit::calibration {
namespace {

using Clock = std::chrono::steady_clock;

// The residuals of every experiment at one parameter vector.
struct Point {
  bool ok = false;
  std::string failure;
  std::vector<Prediction> predictions;
  Eigen::VectorXd residuals;
};

// Runs the experiment models at scaled parameter vectors x (θ_j = x_j·scale_j), caching every point it has run
// (Ceres asks for the same point more than once), and the finite-difference Jacobian dr/dx.
class Evaluator {
public:
  Evaluator(const CalibrationProblem& problem, std::vector<ExperimentModel>& models, double relative_step,
            std::function<bool()> stop_requested)
      : problem_(problem), models_(models), step_(relative_step), stop_requested_(std::move(stop_requested)) {
    for (const ParameterSpec& p : problem.parameters) {
      scale_.push_back(std::abs(p.initial));
      lower_.push_back(p.lower / std::abs(p.initial));
      upper_.push_back(p.upper / std::abs(p.initial));
    }
    for (const ExperimentModel& model : models_) {
      offset_.push_back(residuals_);
      residuals_ += model.residual_count();
    }
  }

  std::size_t residual_count() const { return residuals_; }
  const std::vector<double>& lower() const { return lower_; }
  const std::vector<double>& upper() const { return upper_; }
  std::vector<double> values(const std::vector<double>& x) const {
    std::vector<double> theta(x.size());
    for (std::size_t j = 0; j < x.size(); ++j) theta[j] = x[j] * scale_[j];
    return theta;
  }
  const std::vector<double>& scale() const { return scale_; }
  int model_runs() const { return runs_; }
  bool stopped() const { return stopped_; }
  int warm_started_steps() const { return warm_started_steps_; }

  Point point(const std::vector<double>& x) {
    {
      std::lock_guard lock(mutex_);
      if (auto found = cache_.find(x); found != cache_.end()) return found->second;
    }
    std::vector<Prediction> predictions(models_.size());
    tbb::parallel_for(std::size_t{0}, models_.size(), [&](std::size_t e) {
      if (!fitted(e)) return;
      predictions[e] = run(e, x, nullptr, true);
      // Kept once per experiment, for the finite differences about this point (not in the cache: one field per
      // load step and point would grow with every iteration).
      warm_starts_[e] = {x, std::move(predictions[e].displacements)};
      predictions[e].displacements.reset();
    });
    return store(x, std::move(predictions));
  }

  // A prediction-only experiment (all weights 0) is run once, at the optimum.
  bool fitted(std::size_t e) const { return models_[e].residual_count() > 0; }
  Prediction prediction(std::size_t e, const std::vector<double>& x) { return run(e, x); }

  // dr/dx by one-sided differences (backward at an upper bound); only the experiments whose case holds parameter
  // j are run for column j. Returns empty when a perturbed run fails.
  std::optional<Eigen::MatrixXd> jacobian(const std::vector<double>& x) {
    const Point centre = point(x);
    if (!centre.ok) return std::nullopt;
    const std::size_t n = x.size();
    std::vector<double> h(n);
    std::vector<std::pair<std::size_t, std::size_t>> tasks;  // (parameter, experiment)
    for (std::size_t j = 0; j < n; ++j) {
      h[j] = step_ * std::max(std::abs(x[j]), 1e-3);
      if (x[j] + h[j] > upper_[j]) h[j] = -h[j];
      for (std::size_t e = 0; e < models_.size(); ++e)
        if (models_[e].uses(j) && fitted(e)) tasks.emplace_back(j, e);
    }
    std::vector<Prediction> shifted(tasks.size());
    tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t t) {
      std::vector<double> xs = x;
      xs[tasks[t].first] += h[tasks[t].first];
      // Warm start: each perturbed FE run starts its load steps from the centre run's fields.
      const WarmStart& warm = warm_starts_[tasks[t].second];
      shifted[t] = run(tasks[t].second, xs, warm.x == x ? warm.displacements.get() : nullptr, false);
    });
    Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(residuals_), static_cast<Eigen::Index>(n));
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      if (!shifted[t].ok) return std::nullopt;
      const auto [j, e] = tasks[t];
      const std::vector<double> r = models_[e].residuals(shifted[t]);
      for (std::size_t i = 0; i < r.size(); ++i) {
        const Eigen::Index row = static_cast<Eigen::Index>(offset_[e] + i);
        jac(row, static_cast<Eigen::Index>(j)) = (r[i] - centre.residuals(row)) / h[j];
      }
    }
    return jac;
  }

private:
  Prediction run(std::size_t e, const std::vector<double>& x,
                 const std::vector<insertion::StepDisplacement>* warm_start = nullptr, bool keep = false) {
    Prediction p;
    try {
      p = models_[e].predict(values(x), warm_start, keep, stop_requested_);
    } catch (const InvalidInput& error) {  // e.g. a value the case reader refuses
      p.ok = false;
      p.failure = fmt::format("{}: {}", models_[e].experiment().name, error.what());
    }
    std::lock_guard lock(mutex_);
    stopped_ = stopped_ || p.stopped;
    runs_ += p.model_runs;
    warm_started_steps_ += p.warm_started_steps;
    return p;
  }

  Point store(const std::vector<double>& x, std::vector<Prediction> predictions) {
    Point point;
    point.ok = true;
    point.residuals.resize(static_cast<Eigen::Index>(residuals_));
    for (std::size_t e = 0; e < models_.size(); ++e) {
      if (!fitted(e)) continue;
      if (!predictions[e].ok) {
        point.ok = false;
        point.failure = predictions[e].failure;
        continue;
      }
      const std::vector<double> r = models_[e].residuals(predictions[e]);
      for (std::size_t i = 0; i < r.size(); ++i) point.residuals(static_cast<Eigen::Index>(offset_[e] + i)) = r[i];
    }
    point.predictions = std::move(predictions);
    std::lock_guard lock(mutex_);
    return cache_.emplace(x, std::move(point)).first->second;
  }

  // The FE fields of the last centre point run per experiment.
  struct WarmStart {
    std::vector<double> x;
    std::shared_ptr<const std::vector<insertion::StepDisplacement>> displacements;
  };

  const CalibrationProblem& problem_;
  std::vector<ExperimentModel>& models_;
  std::vector<WarmStart> warm_starts_ = std::vector<WarmStart>(models_.size());
  int warm_started_steps_ = 0;
  double step_;
  std::function<bool()> stop_requested_;  // CalibrationOptions::stop_requested, passed to every FE run
  std::vector<double> scale_, lower_, upper_;
  std::vector<std::size_t> offset_;
  std::size_t residuals_ = 0;
  std::map<std::vector<double>, Point> cache_;
  std::mutex mutex_;
  int runs_ = 0;
  bool stopped_ = false;  // an FE run was stopped on request
};

// All residuals as one Ceres residual block of the scaled parameters.
class ResidualCost final : public ceres::CostFunction {
public:
  explicit ResidualCost(Evaluator& evaluator, int parameters) : evaluator_(evaluator), n_(parameters) {
    set_num_residuals(static_cast<int>(evaluator.residual_count()));
    mutable_parameter_block_sizes()->push_back(parameters);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const std::vector<double> x(parameters[0], parameters[0] + n_);
    const Point p = evaluator_.point(x);
    if (!p.ok) return false;
    for (Eigen::Index i = 0; i < p.residuals.size(); ++i) residuals[i] = p.residuals(i);
    if (jacobians && jacobians[0]) {
      const std::optional<Eigen::MatrixXd> jac = evaluator_.jacobian(x);
      if (!jac) return false;
      for (Eigen::Index i = 0; i < jac->rows(); ++i)
        for (int j = 0; j < n_; ++j) jacobians[0][i * n_ + j] = (*jac)(i, j);
    }
    return true;
  }

private:
  Evaluator& evaluator_;
  int n_;
};

class ProgressCallback final : public ceres::IterationCallback {
public:
  ProgressCallback(const CalibrationOptions& options, const Evaluator& evaluator, const std::vector<double>& x,
                   std::size_t residuals, Clock::time_point start)
      : options_(options), evaluator_(evaluator), x_(x), residuals_(residuals), start_(start) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (options_.progress) {
      CalibrationProgress p;
      p.iteration = summary.iteration;
      p.rms_relative = std::sqrt(2 * summary.cost / std::max<std::size_t>(residuals_, 1));
      p.values = evaluator_.values(x_);
      p.model_runs = evaluator_.model_runs();
      p.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
      if (!options_.progress(p)) {
        stopped_ = true;
        return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
      }
    }
    return ceres::SOLVER_CONTINUE;
  }
  bool stopped() const { return stopped_; }

private:
  const CalibrationOptions& options_;
  const Evaluator& evaluator_;
  const std::vector<double>& x_;  // the parameter block Ceres updates every iteration
  std::size_t residuals_;
  Clock::time_point start_;
  bool stopped_ = false;
};

double rms_of(const std::vector<double>& r) {
  double sum = 0;
  for (double v : r) sum += v * v;
  return r.empty() ? 0.0 : std::sqrt(sum / r.size());
}

// The statistics of the fit at `at` (parameter_statistics.hpp) and, when asked, the FE discretisation error that
// widens the intervals (discretisation_error.hpp); their warnings go to result.
struct OptimumStatistics {
  bool have_jacobian = false;
  ParameterStatistics stats;
  DiscretisationError mesh_error;
};

OptimumStatistics optimum_statistics(const CalibrationProblem& problem, const std::vector<ExperimentModel>& models,
                                     Evaluator& evaluator, const std::vector<double>& at, const Point& p,
                                     CalibrationResult& result) {
  const std::size_t n = problem.parameters.size();
  OptimumStatistics statistics;
  const std::optional<Eigen::MatrixXd> jac = p.ok ? evaluator.jacobian(at) : std::nullopt;
  if (!jac) {
    result.correlation = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n), NAN);
    return statistics;
  }
  statistics.have_jacobian = true;
  const std::vector<double> theta = evaluator.values(at);
  std::vector<std::string> names;
  for (const ParameterSpec& spec : problem.parameters) names.push_back(spec.path);
  Eigen::MatrixXd per_unit = *jac;  // dr/dθ_j = dr/dx_j / scale_j
  for (std::size_t j = 0; j < n; ++j) per_unit.col(static_cast<Eigen::Index>(j)) /= evaluator.scale()[j];
  statistics.stats = parameter_statistics(per_unit, p.residuals, theta, names);
  result.correlation = statistics.stats.correlation;
  result.warnings.insert(result.warnings.end(), statistics.stats.warnings.begin(), statistics.stats.warnings.end());
  if (!problem.solver.mesh_error) return statistics;
  DiscretisationError& mesh_error = statistics.mesh_error;
  mesh_error = discretisation_error(problem, models, theta, per_unit, p.residuals, problem.solver.mesh_error_refinement);
  if (!mesh_error.ok) {
    result.warnings.push_back(fmt::format("the discretisation error was not estimated: {}", mesh_error.failure));
  } else if (!mesh_error.refined.empty()) {
    result.warnings.push_back(fmt::format(
        "the 95 % intervals include the estimated FE discretisation error (the fit re-run at the optimum on "
        "meshes {:g} times finer: {}; first-order Richardson)",
        problem.solver.mesh_error_refinement, fmt::join(mesh_error.refined, ", ")));
  }
  for (const std::string& name : mesh_error.not_refined)
    result.warnings.push_back(fmt::format("{}: its mesh is given (or its curve), so its discretisation error is "
                                          "not in the intervals", name));
  return statistics;
}

// Every parameter's value, standard error and interval (widened by the discretisation error), flagged on a bound.
void add_fitted_parameters(const CalibrationProblem& problem, const std::vector<double>& theta,
                           const OptimumStatistics& statistics, CalibrationResult& result) {
  const DiscretisationError& mesh_error = statistics.mesh_error;
  for (std::size_t j = 0; j < problem.parameters.size(); ++j) {
    FittedParameter fitted;
    fitted.spec = problem.parameters[j];
    fitted.value = theta[j];
    fitted.standard_error = statistics.have_jacobian ? statistics.stats.standard_error[j] : NAN;
    if (statistics.have_jacobian) fitted.ci95 = statistics.stats.ci95[j];
    if (mesh_error.ok && !mesh_error.parameter_error.empty()) {
      fitted.discretisation_error = mesh_error.parameter_error[j];
      if (fitted.ci95) {
        fitted.ci95->first -= fitted.discretisation_error;
        fitted.ci95->second += fitted.discretisation_error;
      }
    }
    const double tolerance = 1e-9 * (fitted.spec.upper - fitted.spec.lower);
    fitted.at_bound = theta[j] <= fitted.spec.lower + tolerance || theta[j] >= fitted.spec.upper - tolerance;
    if (fitted.at_bound) {
      result.warnings.push_back(fmt::format(
          "{}: the optimum lies on a bound ({}); its interval ignores the bound", fitted.spec.path,
          units::format(theta[j], fitted.spec.unit.empty() ? units::si_symbol(fitted.spec.dimension) : fitted.spec.unit)));
    }
    result.parameters.push_back(std::move(fitted));
  }
}

// Every experiment's prediction and residuals at `at` (a prediction-only experiment is run there), and the overall
// relative rms.
void add_experiment_fits(const CalibrationProblem& problem, const std::vector<ExperimentModel>& models,
                         Evaluator& evaluator, const std::vector<double>& at, const Point& p,
                         CalibrationResult& result) {
  std::vector<double> all;
  for (std::size_t e = 0; e < models.size(); ++e) {
    ExperimentFit fit;
    fit.name = problem.experiments[e].name;
    fit.kind = problem.experiments[e].kind;
    fit.predicted_only = !evaluator.fitted(e);
    if (fit.predicted_only) {
      fit.prediction = evaluator.prediction(e, at);
      if (!fit.prediction.ok) result.warnings.push_back(fmt::format("{}: {}", fit.name, fit.prediction.failure));
      for (const std::string& note : fit.prediction.notes) result.warnings.push_back(fit.name + ": " + note);
    } else if (p.ok) {
      fit.prediction = p.predictions[e];
      fit.residuals = models[e].residuals(fit.prediction);
      fit.rms_relative = rms_of(fit.residuals);
      for (const std::string& note : fit.prediction.notes) result.warnings.push_back(fit.name + ": " + note);
    }
    all.insert(all.end(), fit.residuals.begin(), fit.residuals.end());
    result.experiments.push_back(std::move(fit));
  }
  result.rms_relative = rms_of(all);
}

// Ceres' bounded Levenberg-Marquardt from x (updated in place); the result's iterations, status and reason.
void solve_least_squares(const CalibrationProblem& problem, const CalibrationOptions& options, Evaluator& evaluator,
                         std::vector<double>& x, Clock::time_point start, CalibrationResult& result) {
  const std::size_t n = x.size();
  ceres::Problem least_squares;
  least_squares.AddResidualBlock(new ResidualCost(evaluator, static_cast<int>(n)), nullptr, x.data());
  for (std::size_t j = 0; j < n; ++j) {
    least_squares.SetParameterLowerBound(x.data(), static_cast<int>(j), evaluator.lower()[j]);
    least_squares.SetParameterUpperBound(x.data(), static_cast<int>(j), evaluator.upper()[j]);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.max_num_iterations = problem.solver.max_iterations;
  solver.function_tolerance = problem.solver.function_tolerance;
  solver.parameter_tolerance = problem.solver.parameter_tolerance;
  solver.gradient_tolerance = 1e-14;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  solver.update_state_every_iteration = true;
  ProgressCallback callback(options, evaluator, x, evaluator.residual_count(), start);
  solver.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &least_squares, &summary);

  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  switch (summary.termination_type) {
    case ceres::CONVERGENCE: result.status = CalibrationStatus::Converged; break;
    case ceres::NO_CONVERGENCE: result.status = CalibrationStatus::NotConverged; break;
    default: result.status = CalibrationStatus::Failed; break;
  }
  result.reason = summary.message;
  if (callback.stopped()) {
    result.status = CalibrationStatus::Stopped;
    result.reason = fmt::format("stopped on request after iteration {}; the best point so far is kept",
                                result.iterations);
  }
}

void stopped_in_a_run(CalibrationResult& result) {
  result.status = CalibrationStatus::Stopped;
  result.reason = fmt::format("stopped on request during an FE run of iteration {}; the best point so far is kept",
                              std::max(result.iterations, 0));
}

}  // namespace

std::string_view to_string(CalibrationStatus status) { return name_of(kCalibrationStatusNames, status); }

std::vector<double> CalibrationResult::values() const {
  std::vector<double> v;
  for (const FittedParameter& p : parameters) v.push_back(p.value);
  return v;
}

std::string calibrated_case_text(const CalibrationProblem& problem, std::size_t experiment,
                                 const std::vector<double>& values) {
  const ExperimentSpec& e = problem.experiments.at(experiment);
  std::string text = e.case_text;
  for (std::size_t j = 0; j < problem.parameters.size(); ++j) {
    const ParameterSpec& p = problem.parameters[j];
    if (!case_value(text, p.path, e.case_path.string())) continue;
    text = with_case_value(text, p.path, values[j], p.dimension, p.unit, 6);
  }
  return text;
}

CalibrationResult calibrate(const CalibrationProblem& problem, const CalibrationOptions& options) {
  const Clock::time_point start = Clock::now();
  check_ranges(kCalibrationSolverParameters, problem.solver, "calibration solver");  // Python may set any value
  std::vector<ExperimentModel> models;
  bool fe = false, fitted = false;
  for (const ExperimentSpec& e : problem.experiments) {
    models.emplace_back(e, problem.parameters);
    fe = fe || e.kind != ExperimentKind::Design;
    fitted = fitted || models.back().residual_count() > 0;
  }
  if (!fitted) {
    throw InvalidInput(fmt::format("{}: every experiment has zero weights, expected at least one experiment with "
                                   "data to fit (weights = 0 marks a prediction)",
                                   problem.file.string()));
  }
  const double step = problem.solver.relative_step > 0 ? problem.solver.relative_step : (fe ? 1e-3 : 1e-7);
  Evaluator evaluator(problem, models, step, options.stop_requested);
  const std::size_t n = problem.parameters.size();
  std::vector<double> x(n);
  for (std::size_t j = 0; j < n; ++j) x[j] = problem.parameters[j].initial / evaluator.scale()[j];

  CalibrationResult result;
  const auto finish = [&](const std::vector<double>& at) {
    const Point p = evaluator.point(at);
    const OptimumStatistics statistics = optimum_statistics(problem, models, evaluator, at, p, result);
    add_fitted_parameters(problem, evaluator.values(at), statistics, result);
    add_experiment_fits(problem, models, evaluator, at, p, result);
    result.model_runs = evaluator.model_runs() + statistics.mesh_error.model_runs;
    result.warm_started_steps = evaluator.warm_started_steps();
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  };

  // The initial point and its Jacobian: a parameter no experiment depends on is bad input.
  const Point initial = evaluator.point(x);
  if (!initial.ok) {
    if (evaluator.stopped()) {
      stopped_in_a_run(result);
    } else {
      result.status = CalibrationStatus::Failed;
      result.reason = fmt::format("the model fails at the initial values: {}", initial.failure);
    }
    finish(x);
    return result;
  }
  if (const std::optional<Eigen::MatrixXd> jac = evaluator.jacobian(x)) {
    for (std::size_t j = 0; j < n; ++j) {
      if (jac->col(static_cast<Eigen::Index>(j)).norm() == 0) {
        throw InvalidInput(fmt::format("{}: key 'path': no experiment depends on '{}': the residuals do not change "
                                       "when it changes by {:g} %, expected a parameter the measured data depend on",
                                       problem.parameters[j].where, problem.parameters[j].path, 100 * step));
      }
    }
  }
  solve_least_squares(problem, options, evaluator, x, start, result);
  if (result.status != CalibrationStatus::Stopped && evaluator.stopped()) stopped_in_a_run(result);
  finish(x);
  return result;
}

}  // namespace needlekit::calibration
