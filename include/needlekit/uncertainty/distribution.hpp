// Probability distributions of one uncertain input (SI values): normal, truncated normal, lognormal, uniform and
// triangular, each sampled by its quantile function x = F⁻¹(u) of a uniform u ∈ (0, 1) (inverse-transform sampling,
// so that Monte Carlo and quasi-Monte Carlo points map alike). CDFs and quantiles come from Boost.Math.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::uncertainty {

enum class DistributionKind { Normal, TruncatedNormal, Lognormal, Uniform, Triangular };

// The one table of distribution names: {kind, "name", "parameters and meaning"}.
inline constexpr EnumTable<DistributionKind, 5> kDistributionKindNames{{
    {DistributionKind::Normal, "normal", "mean, sd >= 0"},
    {DistributionKind::TruncatedNormal, "truncated-normal", "mean, sd > 0, min < max: the normal restricted to [min, max]"},
    {DistributionKind::Lognormal, "lognormal", "median > 0, sigma_log >= 0 (the sd of ln x)"},
    {DistributionKind::Uniform, "uniform", "min < max"},
    {DistributionKind::Triangular, "triangular", "min < max, mode in [min, max] (default the midpoint)"},
}};
std::string_view to_string(DistributionKind kind);
// Throws InvalidInput naming `what` and listing the names for an unknown name.
DistributionKind distribution_kind_from_string(std::string_view name, std::string_view what);

struct Distribution {
  DistributionKind kind = DistributionKind::Normal;
  double mean = 0;       // normal, truncated-normal: μ (SI); the untruncated normal's mean for truncated-normal
  double sd = 0;         // normal, truncated-normal: σ >= 0 (SI); σ = 0 is the fixed value μ
  double median = 0;     // lognormal: e^μ > 0 (SI)
  double sigma_log = 0;  // lognormal: σ of ln x, >= 0
  double min = 0;        // truncated-normal, uniform, triangular: lower bound (SI), min < max
  double max = 0;        // upper bound (SI)
  double mode = 0;       // triangular: min <= mode <= max
};

// Throws InvalidInput naming `what` (the input's key): negative sd or sigma_log, median <= 0, min >= max, a
// triangular mode outside [min, max], a truncated-normal window with no mass, non-finite parameters.
void validate(const Distribution& distribution, std::string_view what);

// F(x) and F⁻¹(u) for u ∈ (0, 1).
double cdf(const Distribution& distribution, double x);
double quantile(const Distribution& distribution, double u);
double mean(const Distribution& distribution);
// A one-line description with the parameters in the given unit, e.g. "normal(mean 30 um, sd 2 um)".
std::string describe(const Distribution& distribution, double unit_factor, std::string_view unit);

}  // namespace needlekit::uncertainty
