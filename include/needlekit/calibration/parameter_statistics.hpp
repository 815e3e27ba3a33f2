// Uncertainty and identifiability of least-squares parameters from the Jacobian at the optimum (linearised
// statistics, e.g. Bates & Watts 1988, Nonlinear Regression Analysis, §2.3):
//   s² = |r|² / (m − n),  Cov = s² (JᵀJ)⁻¹,  CI95 = θ ± t(0.975, m − n)·√Cov_jj.
// JᵀJ is inverted through the SVD of the column-scaled Jacobian; directions whose singular value is below
// `degeneracy_tolerance` × the largest are combinations the data do not determine: their parameters get no interval
// and a warning names them (e.g. K and S of the post-puncture load, of which only K·S enters the model).
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace needlekit::calibration {

struct ParameterStatistics {
  int degrees_of_freedom = 0;                 // m − n
  double residual_variance = 0;               // s²
  std::vector<double> standard_error;         // per parameter, in its own units; NaN where not identifiable
  std::vector<std::optional<std::pair<double, double>>> ci95;  // empty where not identifiable or m <= n
  Eigen::MatrixXd correlation;                // n × n; NaN where not identifiable
  std::vector<bool> identifiable;
  std::vector<std::string> warnings;
};

struct ParameterStatisticsOptions {
  double degeneracy_tolerance = 1e-6;   // (0, 1): relative singular value below which a direction is not determined
  double correlation_warning = 0.99;    // (0, 1): |correlation| above which two parameters are reported as nearly
                                        // indistinguishable
};

// `jacobian`: m × n derivatives of the residuals by the parameters (per unit of each parameter); `residuals`: m
// values at `values`; `names`: the parameters' names for the warnings.
ParameterStatistics parameter_statistics(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                         const std::vector<double>& values, const std::vector<std::string>& names,
                                         const ParameterStatisticsOptions& options = {});

}  // namespace needlekit::calibration
