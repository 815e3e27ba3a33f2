#include "needle_outcomes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace needlekit::insertion::detail {
namespace {

// N: the needles' total force at the run's depth, linear between the steps (from (0, 0)).
double total_force_at(const std::vector<IndentationStep>& steps, double depth) {
  double previous_depth = 0, previous_force = 0;
  for (const IndentationStep& step : steps) {
    if (step.depth >= depth) {
      const double t = step.depth > previous_depth ? (depth - previous_depth) / (step.depth - previous_depth) : 1.0;
      return previous_force + t * (step.force - previous_force);
    }
    previous_depth = step.depth;
    previous_force = step.force;
  }
  return steps.empty() ? 0.0 : steps.back().force;
}

}  // namespace

NeedleRecorder::NeedleRecorder(const IndentationCase& c)
    : case_(c), needles_(c.needles.size()), samples_(c.needles.size()), work_(c.needles.size(), 0.0) {
  lowest_ = std::numeric_limits<double>::infinity();
  for (const NeedleSite& site : c.needles) lowest_ = std::min(lowest_, site.tip_height);
  for (std::size_t i = 0; i < c.needles.size(); ++i) needles_[i].position = c.needles[i].position;
}

void NeedleRecorder::add(const IndentationStep& step) {
  double total_work = 0;
  for (std::size_t i = 0; i < needles_.size(); ++i) {
    NeedleOutcome& needle = needles_[i];
    const double depth = step.depth - (case_.needles[i].tip_height - lowest_);
    const double previous_depth = needle.depth.empty() ? 0.0 : needle.depth.back();
    const double previous_force = needle.force.empty() ? 0.0 : needle.force.back();
    work_[i] += 0.5 * (previous_force + step.needle_force[i]) * (depth - previous_depth);
    total_work += work_[i];
    needle.depth.push_back(depth);
    needle.force.push_back(step.needle_force[i]);
  }
  const int k = static_cast<int>(punctured_by_step_.size()) + 1;
  for (std::size_t i = 0; i < needles_.size(); ++i) {
    NeedleOutcome& needle = needles_[i];
    if (needle.puncture || !(needle.depth.back() > 0)) continue;  // punctured already, or not at the surface yet
    // Its share of the stored energy: Δ in proportion to the needles' work (quasi-static: work = Δ).
    const double energy = total_work > 0 ? step.strain_energy * work_[i] / total_work : 0.0;
    const double averaged = step.needle_averaged_pressure.empty() ? 0.0 : step.needle_averaged_pressure[i];
    samples_[i].push_back({needle.depth.back(), needle.force.back(), step.needle_contact_area[i], energy, averaged});
    needle.puncture = puncture_point(samples_[i], case_.puncture);
    if (needle.puncture) {
      needle.puncture_step = k;
      ++punctured_;
    }
  }
  punctured_by_step_.push_back(punctured_);
}

std::optional<PuncturePoint> NeedleRecorder::first_puncture(const std::vector<IndentationStep>& steps) const {
  std::optional<PuncturePoint> first;
  for (std::size_t i = 0; i < needles_.size(); ++i) {
    if (!needles_[i].puncture) continue;
    const double depth = needles_[i].puncture->depth + (case_.needles[i].tip_height - lowest_);  // the run's depth
    if (!first || depth < first->depth) first = PuncturePoint{depth, 0.0, needles_[i].puncture->criterion};
  }
  if (first) first->force = total_force_at(steps, first->depth);
  return first;
}

std::vector<NeedleOutcome> NeedleRecorder::needles() const {
  std::vector<NeedleOutcome> needles = needles_;
  for (NeedleOutcome& needle : needles) {
    if (needle.puncture && !needle.depth.empty()) {
      needle.inserted_depth = std::max(0.0, needle.depth.back() - needle.puncture->depth);
    }
  }
  return needles;
}

ArrayOutcome NeedleRecorder::array_outcome(const std::vector<IndentationStep>& steps) const {
  ArrayOutcome array;
  const double count = static_cast<double>(needles_.size());
  for (std::size_t k = 0; k < steps.size() && k < punctured_by_step_.size(); ++k) {
    array.plate_travel.push_back(steps[k].depth + lowest_);
    array.punctured_fraction.push_back(punctured_by_step_[k] / count);
  }
  if (const std::optional<PuncturePoint> first = first_puncture(steps)) {
    array.first_puncture_travel = first->depth + lowest_;
  }
  const std::vector<NeedleOutcome> outcomes = needles();
  double sum = 0, sum_of_squares = 0;
  for (const NeedleOutcome& needle : outcomes) {
    sum += needle.inserted_depth;
    sum_of_squares += needle.inserted_depth * needle.inserted_depth;
  }
  array.mean_inserted_depth = sum / count;
  array.inserted_depth_spread = std::sqrt(std::max(0.0, sum_of_squares / count - array.mean_inserted_depth *
                                                                                  array.mean_inserted_depth));
  array.mean_penetrated_fraction = array.mean_inserted_depth / needle_length(case_);
  return array;
}

}  // namespace needlekit::insertion::detail
