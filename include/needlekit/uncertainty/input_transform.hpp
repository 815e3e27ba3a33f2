// From uniform points to input values: every uncertain input has a distribution and a physical window (e.g. a
// diameter > 0); the sample is drawn from the distribution restricted to that window, x = F⁻¹(F(lo) + u·(F(hi) −
// F(lo))). Correlated inputs go through a Gaussian copula (the Nataf transform; Liu & Der Kiureghian, Prob. Eng.
// Mech. 1(2), 1986): z = Φ⁻¹(u), z' = L·z with L·Lᵀ = R (the correlation matrix of the normal scores), u' = Φ(z').
// The correlation is specified between the normal scores; for non-normal marginals the correlation of the values
// themselves is slightly smaller in magnitude.
#pragma once
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "needlekit/uncertainty/distribution.hpp"

namespace needlekit::uncertainty {

struct UncertainInput {
  std::string key;                 // as the user wrote it, e.g. "needle.tip_diameter"
  Distribution distribution;
  double lower = -std::numeric_limits<double>::infinity();  // physical window (SI): samples are drawn from the
  double upper = std::numeric_limits<double>::infinity();   // distribution truncated to [lower, upper]
};

// Correlation between the normal scores of inputs `first` and `second` (indices into the input list), in (-1, 1).
struct Correlation {
  std::size_t first = 0;
  std::size_t second = 0;
  double rho = 0;
};

// P(x outside [lower, upper]) for the untruncated distribution (the mass the window removes).
double mass_outside_window(const UncertainInput& input);

class InputTransform {
public:
  // Throws InvalidInput (naming the keys) for invalid distributions, a window with no mass, correlations outside
  // (-1, 1), repeated or self pairs, or a correlation matrix that is not positive definite.
  InputTransform(std::vector<UncertainInput> inputs, const std::vector<Correlation>& correlations = {});

  std::size_t size() const { return inputs_.size(); }
  const std::vector<UncertainInput>& inputs() const { return inputs_; }
  bool correlated() const { return correlated_; }

  // x = T(u) for one row of k uniforms (thread-safe).
  void values(const double* u, double* x) const;
  // The value of input i alone for a uniform u (valid only without correlations).
  double value(std::size_t i, double u) const;

private:
  std::vector<UncertainInput> inputs_;
  std::vector<double> window_lo_, window_hi_;  // F(lower), F(upper)
  bool correlated_ = false;
  Eigen::MatrixXd cholesky_;                   // L of R = L·Lᵀ
};

}  // namespace needlekit::uncertainty
