// The discretisation error of fitted parameters: how far the optimum would move if the FE experiments ran on finer
// meshes. The residuals at the optimum are recomputed on meshes `refinement` times finer (size_at_tip and size_far),
// Δr = r_fine − r_fit; the finer model's optimum lies at θ + δ with the Gauss-Newton step δ = −J⁺Δr (J the
// Jacobian at the optimum); with an error linear in the element size (the flat punch's observed order, about 1:
// tests/verification/test_fem_flat_punch.cpp), the fit mesh's own error is Richardson's δ / (1 − refinement). The
// calibration widens each 95 % interval by its magnitude: the intervals of the noise alone missed a mesh bias of
// 1.1 % in E (docs/calibration.md).
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "needlekit/calibration/calibration_problem.hpp"
#include "needlekit/calibration/experiment_model.hpp"

namespace needlekit::calibration {

struct DiscretisationError {
  std::vector<double> parameter_error;   // SI, >= 0, per parameter: |δ| / (1 − refinement); 0 where not estimated
  std::vector<std::string> refined;      // the experiments re-run on finer meshes
  std::vector<std::string> not_refined;  // FE experiments that could not be (a given .msh mesh or pre-puncture curve)
  int model_runs = 0;                    // FE runs on the finer meshes
  bool ok = false;                       // false: a finer run failed (parameter_error all 0, `failure` says why)
  std::string failure;
};

// `models`: the fit's models (in the order of problem.experiments; their residuals stacked in that order make
// `residuals` and the rows of `jacobian`, m × n per unit of each parameter); `values`: the optimum, SI.
DiscretisationError discretisation_error(const CalibrationProblem& problem, const std::vector<ExperimentModel>& models,
                                         const std::vector<double>& values, const Eigen::MatrixXd& jacobian,
                                         const Eigen::VectorXd& residuals, double refinement);

}  // namespace needlekit::calibration
