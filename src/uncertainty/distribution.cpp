#include "needlekit/uncertainty/distribution.hpp"

#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/triangular.hpp>
#include <boost/math/distributions/uniform.hpp>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::uncertainty {
namespace {

// Domain errors are checked by validate(); Boost.Math must not throw or print on them.
// Double precision throughout (Boost.Math would otherwise evaluate in long double, 3x slower, for no gain in the
// 53-bit results sampling needs).
using Policy = boost::math::policies::policy<boost::math::policies::domain_error<boost::math::policies::ignore_error>,
                                             boost::math::policies::overflow_error<boost::math::policies::ignore_error>,
                                             boost::math::policies::promote_double<false>>;
using Normal = boost::math::normal_distribution<double, Policy>;

double standard_normal_cdf(double z) { return boost::math::cdf(Normal(0, 1), z); }
double standard_normal_quantile(double u) { return boost::math::quantile(Normal(0, 1), u); }

// The truncated normal's CDF values at its bounds.
std::pair<double, double> truncation_window(const Distribution& d) {
  return {standard_normal_cdf((d.min - d.mean) / d.sd), standard_normal_cdf((d.max - d.mean) / d.sd)};
}

[[noreturn]] void fail(std::string_view what, std::string_view problem) {
  throw InvalidInput(fmt::format("{}: {}", what, problem));
}

}  // namespace

std::string_view to_string(DistributionKind kind) { return name_of(kDistributionKindNames, kind); }

DistributionKind distribution_kind_from_string(std::string_view name, std::string_view what) {
  return value_of(kDistributionKindNames, name, what);
}

void validate(const Distribution& d, std::string_view what) {
  for (double value : {d.mean, d.sd, d.median, d.sigma_log, d.min, d.max, d.mode}) {
    if (!std::isfinite(value)) fail(what, "a distribution parameter is not finite, expected finite values");
  }
  switch (d.kind) {
    case DistributionKind::Normal:
      if (d.sd < 0) fail(what, fmt::format("sd {:g} is negative, expected sd >= 0", d.sd));
      break;
    case DistributionKind::TruncatedNormal: {
      if (!(d.sd > 0)) fail(what, fmt::format("sd {:g} is not positive, expected sd > 0", d.sd));
      if (!(d.min < d.max)) fail(what, fmt::format("min {:g} >= max {:g} (SI), expected min < max", d.min, d.max));
      const auto [lo, hi] = truncation_window(d);
      if (!(hi - lo > 1e-12)) {
        fail(what, "the window [min, max] holds no mass of the normal (more than 7 sd from the mean), expected a "
                   "window near the mean");
      }
      break;
    }
    case DistributionKind::Lognormal:
      if (!(d.median > 0)) fail(what, fmt::format("median {:g} is not positive, expected median > 0", d.median));
      if (d.sigma_log < 0) fail(what, fmt::format("sigma_log {:g} is negative, expected sigma_log >= 0", d.sigma_log));
      break;
    case DistributionKind::Uniform:
      if (!(d.min < d.max)) fail(what, fmt::format("min {:g} >= max {:g} (SI), expected min < max", d.min, d.max));
      break;
    case DistributionKind::Triangular:
      if (!(d.min < d.max)) fail(what, fmt::format("min {:g} >= max {:g} (SI), expected min < max", d.min, d.max));
      if (!(d.mode >= d.min && d.mode <= d.max)) {
        fail(what, fmt::format("mode {:g} is outside [min, max] = [{:g}, {:g}] (SI)", d.mode, d.min, d.max));
      }
      break;
  }
}

double cdf(const Distribution& d, double x) {
  switch (d.kind) {
    case DistributionKind::Normal:
      if (d.sd == 0) return x < d.mean ? 0.0 : 1.0;
      return standard_normal_cdf((x - d.mean) / d.sd);
    case DistributionKind::TruncatedNormal: {
      if (x <= d.min) return 0;
      if (x >= d.max) return 1;
      const auto [lo, hi] = truncation_window(d);
      return (standard_normal_cdf((x - d.mean) / d.sd) - lo) / (hi - lo);
    }
    case DistributionKind::Lognormal:
      if (x <= 0) return 0;
      if (d.sigma_log == 0) return x < d.median ? 0.0 : 1.0;
      return standard_normal_cdf(std::log(x / d.median) / d.sigma_log);
    case DistributionKind::Uniform:
      return boost::math::cdf(boost::math::uniform_distribution<double, Policy>(d.min, d.max),
                              std::clamp(x, d.min, d.max));
    case DistributionKind::Triangular:
      return boost::math::cdf(boost::math::triangular_distribution<double, Policy>(d.min, d.mode, d.max),
                              std::clamp(x, d.min, d.max));
  }
  return 0;
}

double quantile(const Distribution& d, double u) {
  switch (d.kind) {
    case DistributionKind::Normal: return d.mean + d.sd * standard_normal_quantile(u);
    case DistributionKind::TruncatedNormal: {
      const auto [lo, hi] = truncation_window(d);
      return std::clamp(d.mean + d.sd * standard_normal_quantile(lo + u * (hi - lo)), d.min, d.max);
    }
    case DistributionKind::Lognormal: return d.median * std::exp(d.sigma_log * standard_normal_quantile(u));
    case DistributionKind::Uniform: return d.min + u * (d.max - d.min);
    case DistributionKind::Triangular:
      return boost::math::quantile(boost::math::triangular_distribution<double, Policy>(d.min, d.mode, d.max), u);
  }
  return 0;
}

double mean(const Distribution& d) {
  switch (d.kind) {
    case DistributionKind::Normal: return d.mean;
    case DistributionKind::TruncatedNormal: {
      const auto [lo, hi] = truncation_window(d);
      const boost::math::normal_distribution<double, Policy> unit(0, 1);
      const double a = boost::math::pdf(unit, (d.min - d.mean) / d.sd);
      const double b = boost::math::pdf(unit, (d.max - d.mean) / d.sd);
      return d.mean + d.sd * (a - b) / (hi - lo);
    }
    case DistributionKind::Lognormal: return d.median * std::exp(0.5 * d.sigma_log * d.sigma_log);
    case DistributionKind::Uniform: return 0.5 * (d.min + d.max);
    case DistributionKind::Triangular: return (d.min + d.mode + d.max) / 3;
  }
  return 0;
}

std::string describe(const Distribution& d, double factor, std::string_view unit) {
  const auto q = [&](double value) { return fmt::format("{:.6g} {}", value / factor, unit); };
  switch (d.kind) {
    case DistributionKind::Normal: return fmt::format("normal(mean {}, sd {})", q(d.mean), q(d.sd));
    case DistributionKind::TruncatedNormal:
      return fmt::format("truncated-normal(mean {}, sd {}, min {}, max {})", q(d.mean), q(d.sd), q(d.min), q(d.max));
    case DistributionKind::Lognormal:
      return fmt::format("lognormal(median {}, sigma_log {:.6g})", q(d.median), d.sigma_log);
    case DistributionKind::Uniform: return fmt::format("uniform(min {}, max {})", q(d.min), q(d.max));
    case DistributionKind::Triangular:
      return fmt::format("triangular(min {}, mode {}, max {})", q(d.min), q(d.mode), q(d.max));
  }
  return "?";
}

}  // namespace needlekit::uncertainty
