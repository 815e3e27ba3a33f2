#include "needlekit/insertion/puncture_criteria.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string_view>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/puncture_parameters.hpp"

namespace needlekit::insertion {
namespace {

// The first point where g(sample) >= 0, interpolated linearly in depth and force between the bracketing samples.
std::optional<PuncturePoint> first_crossing(const std::vector<PunctureSample>& samples,
                                            const std::function<double(const PunctureSample&)>& g,
                                            PunctureCriterion criterion) {
  double previous = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double value = g(samples[k]);
    if (value >= 0) {
      PuncturePoint point{samples[k].depth, samples[k].force, criterion};
      if (k > 0 && value > previous) {
        const double t = -previous / (value - previous);  // previous < 0 <= value
        point.depth = samples[k - 1].depth + t * (samples[k].depth - samples[k - 1].depth);
        point.force = samples[k - 1].force + t * (samples[k].force - samples[k - 1].force);
      }
      return point;
    }
    previous = value;
  }
  return std::nullopt;
}

void require_positive(double value, std::string_view what, std::string_view unit) {
  if (!std::isfinite(value) || !(value > 0)) {
    throw InvalidInput(fmt::format("{}: {} {} is not positive, expected a positive finite value", what, value, unit));
  }
}

void validate_curve(const ForceDepthCurve& curve, std::string_view what) {
  if (curve.depth.size() != curve.force.size()) {
    throw InvalidInput(fmt::format("{}: {} depths but {} forces, expected one force per depth", what,
                                   curve.depth.size(), curve.force.size()));
  }
  if (curve.depth.size() < 2) {
    throw InvalidInput(fmt::format("{}: {} samples, expected at least 2", what, curve.depth.size()));
  }
  for (std::size_t i = 0; i < curve.depth.size(); ++i) {
    if (!std::isfinite(curve.depth[i]) || !std::isfinite(curve.force[i])) {
      throw InvalidInput(fmt::format("{}: sample {} is not finite", what, i + 1));
    }
    if (i > 0 && !(curve.depth[i] > curve.depth[i - 1])) {
      throw InvalidInput(fmt::format("{}: depth {} m at sample {} does not increase (previous {} m), expected "
                                     "strictly increasing depths",
                                     what, curve.depth[i], i + 1, curve.depth[i - 1]));
    }
  }
}

// Piecewise-linear interpolation; x inside [depth.front(), depth.back()].
double force_at(const ForceDepthCurve& curve, double x) {
  const auto upper = std::upper_bound(curve.depth.begin(), curve.depth.end(), x);
  if (upper == curve.depth.begin()) return curve.force.front();
  if (upper == curve.depth.end()) return curve.force.back();
  const std::size_t i = static_cast<std::size_t>(upper - curve.depth.begin());
  const double t = (x - curve.depth[i - 1]) / (curve.depth[i] - curve.depth[i - 1]);
  return curve.force[i - 1] + t * (curve.force[i] - curve.force[i - 1]);
}

}  // namespace

double contact_pressure(const PunctureSample& sample) {
  return sample.contact_area > 0 ? sample.force / sample.contact_area : 0.0;  // Eq 3.17: P_s = F/dA
}

void validate(const PunctureOptions& options) {
  check_ranges(kPunctureParameters, options, "puncture");
  if (options.criterion != PunctureLaw::AveragedPressure) return;
  if (!options.critical_pressure) {
    throw InvalidInput("puncture.criterion: \"averaged-pressure\" without a critical_pressure, expected "
                       "critical_pressure = the pressure p_c that the averaged contact pressure reaches at puncture");
  }
  if (options.toughness) {
    throw InvalidInput("puncture.toughness: given with criterion = \"averaged-pressure\", which reads no toughness; "
                       "expected criterion = \"dissertation\" for the fracture-energy criterion, or no toughness");
  }
}

std::optional<PuncturePoint> critical_pressure_puncture(const std::vector<PunctureSample>& samples,
                                                        double critical_pressure) {
  require_positive(critical_pressure, "critical_pressure", "Pa");
  // Before contact (A = 0) the pressure is 0 by definition, so g = -P_c there.
  return first_crossing(
      samples, [&](const PunctureSample& s) { return contact_pressure(s) - critical_pressure; },
      PunctureCriterion::CriticalPressure);
}

std::optional<PuncturePoint> fracture_energy_puncture(const std::vector<PunctureSample>& samples, double toughness) {
  require_positive(toughness, "toughness", "J/m^2");
  // Eq 3.14 at the instant of cracking (dx = 0): J·dA = -dΔ; a crack over the contact area forms when the stored
  // energy can pay for it. Normalised by J·A so that the interpolation weights the two terms alike; no contact, no
  // crack (g = -1).
  return first_crossing(
      samples,
      [&](const PunctureSample& s) {
        const double cost = toughness * s.contact_area;
        return cost > 0 ? s.strain_energy / cost - 1.0 : -1.0;
      },
      PunctureCriterion::FractureEnergy);
}

std::optional<PuncturePoint> averaged_pressure_puncture(const std::vector<PunctureSample>& samples,
                                                        double critical_pressure) {
  require_positive(critical_pressure, "critical_pressure", "Pa");
  return first_crossing(
      samples, [&](const PunctureSample& s) { return s.averaged_pressure - critical_pressure; },
      PunctureCriterion::AveragedPressure);
}

std::optional<PuncturePoint> puncture_point(const std::vector<PunctureSample>& samples,
                                            const PunctureOptions& options) {
  validate(options);
  if (options.criterion == PunctureLaw::AveragedPressure) {
    return averaged_pressure_puncture(samples, *options.critical_pressure);
  }
  std::optional<PuncturePoint> best;
  if (options.critical_pressure) best = critical_pressure_puncture(samples, *options.critical_pressure);
  if (options.toughness) {
    const auto energy = fracture_energy_puncture(samples, *options.toughness);
    if (energy && (!best || energy->depth < best->depth)) best = energy;
  }
  return best;
}

ToughnessResult two_insertion_toughness(const ForceDepthCurve& first, const ForceDepthCurve& second,
                                        const ToughnessOptions& options) {
  validate_curve(first, "first insertion");
  validate_curve(second, "second insertion");
  require_positive(options.crack_area, "crack_area", "m^2");
  if (!std::isfinite(options.min_depth) || options.min_depth < 0) {
    throw InvalidInput(fmt::format("min_depth: {} m is negative, expected >= 0", options.min_depth));
  }
  ToughnessResult result;
  result.min_depth = std::max({options.min_depth, first.depth.front(), second.depth.front()});
  result.max_depth = std::min(first.depth.back(), second.depth.back());
  if (options.max_depth) result.max_depth = std::min(result.max_depth, *options.max_depth);
  if (!(result.max_depth > result.min_depth)) {
    throw InvalidInput(fmt::format("two-insertion range: [{} m, {} m] is empty, expected the curves to overlap "
                                   "within [min_depth, max_depth]",
                                   result.min_depth, result.max_depth));
  }
  // Both curves are linear between the union of their sample depths: the trapezoid rule is exact there.
  std::vector<double> x{result.min_depth, result.max_depth};
  for (const ForceDepthCurve* curve : {&first, &second}) {
    for (double d : curve->depth) {
      if (d > result.min_depth && d < result.max_depth) x.push_back(d);
    }
  }
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double difference_left = force_at(first, x[i - 1]) - force_at(second, x[i - 1]);
    const double difference_right = force_at(first, x[i]) - force_at(second, x[i]);
    result.energy += 0.5 * (difference_left + difference_right) * (x[i] - x[i - 1]);
  }
  result.toughness = result.energy / options.crack_area;  // Eq 3.16: J = (F - F') dx / dA
  return result;
}

}  // namespace needlekit::insertion
