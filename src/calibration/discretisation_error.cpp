#include "needlekit/calibration/discretisation_error.hpp"

#include <Eigen/SVD>
#include <cmath>

namespace needlekit::calibration {

DiscretisationError discretisation_error(const CalibrationProblem& problem, const std::vector<ExperimentModel>& models,
                                         const std::vector<double>& values, const Eigen::MatrixXd& jacobian,
                                         const Eigen::VectorXd& residuals, double refinement) {
  DiscretisationError out;
  const Eigen::Index n = jacobian.cols();
  out.parameter_error.assign(static_cast<std::size_t>(n), 0.0);
  Eigen::VectorXd change = Eigen::VectorXd::Zero(residuals.size());  // Δr = r_fine − r_fit
  std::size_t offset = 0;
  for (std::size_t e = 0; e < models.size(); ++e) {
    const ExperimentModel& model = models[e];
    const std::size_t count = model.residual_count();
    if (count > 0 && problem.experiments[e].kind != ExperimentKind::Design) {
      if (!model.meshes_block()) {
        out.not_refined.push_back(problem.experiments[e].name);
      } else {
        // Built here, one at a time: Gmsh is not thread-safe.
        const ExperimentModel finer(problem.experiments[e], problem.parameters, refinement);
        const Prediction prediction = finer.predict(values);
        out.model_runs += prediction.model_runs;
        if (!prediction.ok) {
          out.failure = prediction.failure;
          return out;
        }
        const std::vector<double> r = finer.residuals(prediction);
        for (std::size_t i = 0; i < count; ++i) {
          change(static_cast<Eigen::Index>(offset + i)) = r[i] - residuals(static_cast<Eigen::Index>(offset + i));
        }
        out.refined.push_back(problem.experiments[e].name);
      }
    }
    offset += count;
  }
  out.ok = true;
  if (out.refined.empty()) return out;
  // δ = −J⁺Δr in relative coordinates (columns scaled by the values), directions the data do not determine left out
  // as in parameter_statistics.hpp.
  Eigen::MatrixXd scaled = jacobian;
  for (Eigen::Index j = 0; j < n; ++j) scaled.col(j) *= values[static_cast<std::size_t>(j)];
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinU | Eigen::ComputeThinV);
  svd.setThreshold(1e-6);
  const Eigen::VectorXd relative = -svd.solve(change);
  for (Eigen::Index j = 0; j < n; ++j) {
    out.parameter_error[static_cast<std::size_t>(j)] =
        std::abs(relative(j) * values[static_cast<std::size_t>(j)]) / (1 - refinement);
  }
  return out;
}

}  // namespace needlekit::calibration
