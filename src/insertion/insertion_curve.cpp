#include "needlekit/insertion/insertion_curve.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/insertion_curve_parameters.hpp"

namespace needlekit::insertion {
namespace {

// Linear interpolation of the pre-puncture curve at depth x >= 0, from (0, 0) to its first sample; held at its last.
double pre_puncture_force_at(const ForceDepthCurve& curve, double x) {
  if (x <= 0) return 0;
  const auto& depth = curve.depth;
  const auto it = std::lower_bound(depth.begin(), depth.end(), x);
  if (it == depth.end()) return curve.force.back();
  const std::size_t j = static_cast<std::size_t>(it - depth.begin());
  if (depth[j] == x) return curve.force[j];
  const double x0 = j == 0 ? 0.0 : depth[j - 1], f0 = j == 0 ? 0.0 : curve.force[j - 1];
  return f0 + (curve.force[j] - f0) * (x - x0) / (depth[j] - x0);
}

struct Sample {
  double displacement = 0;
  bool after_punctures = false;  // at a puncture displacement: the sample after the relaxation drop
  bool operator<(const Sample& other) const {
    return displacement < other.displacement ||
           (displacement == other.displacement && !after_punctures && other.after_punctures);
  }
  bool operator==(const Sample& other) const {
    return displacement == other.displacement && after_punctures == other.after_punctures;
  }
};

}  // namespace

std::string_view to_string(InsertionPhase phase) { return name_of(kInsertionPhaseNames, phase); }

std::string_view to_string(InsertionStatus status) { return name_of(kInsertionStatusNames, status); }

namespace {

void validate_needle(const NeedleInsertion& needle, std::size_t i) {
  const std::string what = fmt::format("needle {} pre-puncture curve", i + 1);
  validate_force_curve(needle.pre_puncture.curve, what);
  if (needle.pre_puncture.curve.depth.front() < 0)
    throw InvalidInput(fmt::format("{}: first depth {:.6g} m, expected depths >= 0", what,
                                   needle.pre_puncture.curve.depth.front()));
  if (needle.loads == nullptr) throw InvalidInput(fmt::format("needle {}: no post-puncture loads given", i + 1));
  if (!(needle.stiffness > 0) || !std::isfinite(needle.stiffness))
    throw InvalidInput(fmt::format("needle {} stiffness: {} N/m^2, expected a finite value > 0", i + 1,
                                   needle.stiffness));
  if (!(needle.scale > 0) || !std::isfinite(needle.scale))
    throw InvalidInput(fmt::format("needle {} scale: {}, expected a finite value > 0", i + 1, needle.scale));
  if (!(needle.contact_offset >= 0) || !std::isfinite(needle.contact_offset))
    throw InvalidInput(fmt::format("needle {} contact_offset: {} m, expected a finite length >= 0", i + 1,
                                   needle.contact_offset));
  const double last = needle.pre_puncture.curve.depth.back();
  if (needle.pre_puncture.puncture) {
    const double x = needle.pre_puncture.puncture->depth;
    if (!(x > 0) || x > last * (1 + 1e-12))
      throw InvalidInput(fmt::format("{}: puncture depth {:.6g} m, expected a depth in (0, {:.6g}] m (within the "
                                     "curve)",
                                     what, x, last));
  }
}

// Samples: every pre-puncture sample until its needle punctures, both sides of every puncture, and an equally
// spaced cutting grid from the first puncture to the end; sorted, without repeats.
std::vector<Sample> curve_samples(const std::vector<NeedleInsertion>& needles,
                                  const std::vector<double>& puncture_displacement, double end, int cutting_samples) {
  std::vector<Sample> samples{{0.0, false}};
  double first_puncture = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < needles.size(); ++i) {
    const double offset = needles[i].contact_offset;
    for (double x : needles[i].pre_puncture.curve.depth) {
      const double u = offset + x;
      if (u <= end && u <= puncture_displacement[i]) samples.push_back({u, false});
    }
    if (puncture_displacement[i] <= end) {
      samples.push_back({puncture_displacement[i], false});
      samples.push_back({puncture_displacement[i], true});
      first_puncture = std::min(first_puncture, puncture_displacement[i]);
    }
  }
  if (first_puncture <= end)
    for (int k = 1; k <= cutting_samples; ++k)
      samples.push_back({first_puncture + (end - first_puncture) * k / static_cast<double>(cutting_samples), false});
  std::sort(samples.begin(), samples.end());
  samples.erase(std::unique(samples.begin(), samples.end()), samples.end());
  return samples;
}

// Needle i's force at every sample (pre-puncture curve before its puncture, Eq 3.20's cutting force after it), kept as
// result.needle_force[i] and added to result.force, and its puncture event.
void add_needle(const NeedleInsertion& needle, std::size_t i, double puncture_displacement, double end,
                const std::vector<Sample>& samples, InsertionCurve& result) {
  std::vector<double>& own = result.needle_force[i];
  own.assign(samples.size(), 0.0);
  std::vector<std::size_t> cutting;
  std::vector<double> cutting_depth;
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const double x = samples[s].displacement - needle.contact_offset;
    const bool punctured = samples[s].displacement > puncture_displacement ||
                           (samples[s].displacement == puncture_displacement && samples[s].after_punctures);
    if (punctured) {
      cutting.push_back(s);
      cutting_depth.push_back(x);
      ++result.punctured_needles[s];
    } else {
      own[s] = pre_puncture_force_at(needle.pre_puncture.curve, x);
    }
  }
  const std::vector<double> cut = post_puncture_forces(*needle.loads, cutting_depth, needle.stiffness, needle.scale);
  for (std::size_t k = 0; k < cutting.size(); ++k) own[cutting[k]] = cut[k];
  for (std::size_t s = 0; s < samples.size(); ++s) result.force[s] += own[s];
  if (puncture_displacement <= end) {
    PunctureEvent event;
    event.needle = static_cast<int>(i);
    event.displacement = puncture_displacement;
    event.depth = needle.pre_puncture.puncture->depth;
    event.force_before = pre_puncture_force_at(needle.pre_puncture.curve, event.depth);
    event.force_after = post_puncture_force(*needle.loads, event.depth, needle.stiffness, needle.scale);
    event.drop = event.force_before - event.force_after;
    result.punctures.push_back(event);
  }
}

}  // namespace

InsertionCurve insertion_curve(const std::vector<NeedleInsertion>& needles, const InsertionCurveOptions& options) {
  if (needles.empty()) throw InvalidInput("needles: none given, expected at least one needle");
  check_ranges(kInsertionCurveParameters, options, "insertion curve");

  const std::size_t count = needles.size();
  std::vector<double> puncture_displacement(count, std::numeric_limits<double>::infinity());
  double end = options.final_depth;
  InsertionCurve result;
  for (std::size_t i = 0; i < count; ++i) {
    const NeedleInsertion& needle = needles[i];
    validate_needle(needle, i);
    const double last = needle.pre_puncture.curve.depth.back();
    if (needle.pre_puncture.puncture) {
      puncture_displacement[i] = needle.contact_offset + needle.pre_puncture.puncture->depth;
    } else if (needle.contact_offset + last < end) {
      end = needle.contact_offset + last;
      result.status = InsertionStatus::NoPuncture;
      result.reason = fmt::format("needle {} did not puncture within its pre-puncture curve (to {:.6g} um); the "
                                  "curve stops at a displacement of {:.6g} um",
                                  i + 1, last * 1e6, end * 1e6);
    }
  }
  if (result.reason.empty())
    result.reason = fmt::format("reached the final depth {:.6g} um", options.final_depth * 1e6);

  const std::vector<Sample> samples = curve_samples(needles, puncture_displacement, end, options.cutting_samples);
  const std::size_t m = samples.size();
  result.depth.resize(m);
  result.force.assign(m, 0.0);
  result.punctured_needles.assign(m, 0);
  result.phase.assign(m, InsertionPhase::Indentation);
  result.needle_force.resize(count);
  for (std::size_t s = 0; s < m; ++s) result.depth[s] = samples[s].displacement;
  for (std::size_t i = 0; i < count; ++i) add_needle(needles[i], i, puncture_displacement[i], end, samples, result);
  for (std::size_t s = 0; s < m; ++s)
    if (result.punctured_needles[s] > 0) result.phase[s] = InsertionPhase::Cutting;
  std::stable_sort(result.punctures.begin(), result.punctures.end(),
                   [](const PunctureEvent& a, const PunctureEvent& b) { return a.displacement < b.displacement; });
  return result;
}

}  // namespace needlekit::insertion
