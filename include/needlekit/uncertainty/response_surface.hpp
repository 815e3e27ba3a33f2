// A quadratic response surface in the logarithms of positive inputs, fitted by least squares (Myers, Montgomery &
// Anderson-Cook, Response Surface Methodology, 4th ed., Wiley 2016, §3 and §6): with z_i = ln(x_i / x̂_i) (x̂ the
// nominal inputs),
//   ln y ≈ b0 + Σ_i b_i z_i + Σ_{i<=j} b_ij z_i z_j,   p = 1 + k + k(k+1)/2 terms for k inputs,
// a power law in each input with interactions; for y = c·Π x_i^a_i it is exact. The coefficients minimise
// Σ_r (ln y_r − ln ŷ_r)² over the runs (Eigen's column-pivoting Householder QR, rank-revealing).
#pragma once
#include <Eigen/Core>
#include <vector>

namespace needlekit::uncertainty {

class LogQuadraticSurface {
public:
  LogQuadraticSurface() = default;
  // inputs[r]: the k inputs of run r (> 0), outputs[r] > 0. Throws InvalidInput for fewer runs than terms, a
  // non-positive value or a rank-deficient design.
  LogQuadraticSurface(std::vector<double> nominal, const std::vector<std::vector<double>>& inputs,
                      const std::vector<double>& outputs);

  static int terms(int inputs) { return 1 + inputs + inputs * (inputs + 1) / 2; }
  double operator()(const double* x) const;  // ŷ(x) = exp(polynomial)
  const Eigen::VectorXd& coefficients() const { return coefficients_; }

private:
  Eigen::VectorXd features(const double* x) const;
  std::vector<double> nominal_;
  Eigen::VectorXd coefficients_;
};

}  // namespace needlekit::uncertainty
