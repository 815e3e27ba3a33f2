#include "needlekit/uncertainty/response_surface.hpp"

#include <Eigen/QR>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::uncertainty {

LogQuadraticSurface::LogQuadraticSurface(std::vector<double> nominal, const std::vector<std::vector<double>>& inputs,
                                         const std::vector<double>& outputs)
    : nominal_(std::move(nominal)) {
  const int k = static_cast<int>(nominal_.size());
  const int p = terms(k);
  const auto n = static_cast<int>(inputs.size());
  if (n < p || outputs.size() != inputs.size()) {
    throw InvalidInput(fmt::format("response surface: {} runs for {} terms, expected at least as many runs", n, p));
  }
  Eigen::MatrixXd a(n, p);
  Eigen::VectorXd b(n);
  for (int r = 0; r < n; ++r) {
    for (int i = 0; i < k; ++i) {
      if (!(inputs[r][i] > 0)) throw InvalidInput("response surface: an input is not positive");
    }
    if (!(outputs[r] > 0)) throw InvalidInput("response surface: an output is not positive");
    a.row(r) = features(inputs[r].data()).transpose();
    b(r) = std::log(outputs[r]);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < p) {
    throw InvalidInput(fmt::format("response surface: the design of {} runs has rank {} < {} terms", n, qr.rank(), p));
  }
  coefficients_ = qr.solve(b);
}

Eigen::VectorXd LogQuadraticSurface::features(const double* x) const {
  const int k = static_cast<int>(nominal_.size());
  Eigen::VectorXd f(terms(k));
  std::vector<double> z(k);
  for (int i = 0; i < k; ++i) z[i] = std::log(x[i] / nominal_[i]);
  int t = 0;
  f(t++) = 1;
  for (int i = 0; i < k; ++i) f(t++) = z[i];
  for (int i = 0; i < k; ++i) {
    for (int j = i; j < k; ++j) f(t++) = z[i] * z[j];
  }
  return f;
}

double LogQuadraticSurface::operator()(const double* x) const { return std::exp(features(x).dot(coefficients_)); }

}  // namespace needlekit::uncertainty
