// The per-needle record of an indentation run: each needle's force and depth per step, its own puncture point, and
// the totals of a needle array (insertion/indentation.hpp: NeedleOutcome, ArrayOutcome).
#pragma once
#include <optional>
#include <vector>

#include "needlekit/insertion/indentation.hpp"

namespace needlekit::insertion::detail {

// Fed every converged step of the case (of the whole array), in order; evaluates each needle's puncture criteria on
// its own force, contact area and share of the stored energy (Δ times its part of the needles' work).
class NeedleRecorder {
 public:
  explicit NeedleRecorder(const IndentationCase& indentation_case);

  void add(const IndentationStep& step);
  bool all_punctured() const { return punctured_ == static_cast<int>(needles_.size()); }
  // The earliest needle's puncture, at the run's depth, with the needles' total force there (interpolated between
  // the steps); empty when no needle punctured.
  std::optional<PuncturePoint> first_puncture(const std::vector<IndentationStep>& steps) const;
  std::vector<NeedleOutcome> needles() const;
  ArrayOutcome array_outcome(const std::vector<IndentationStep>& steps) const;

 private:
  const IndentationCase& case_;
  double lowest_ = 0;                                // m, the smallest tip height
  std::vector<NeedleOutcome> needles_;
  std::vector<std::vector<PunctureSample>> samples_;  // per needle
  std::vector<double> work_;                          // J, per needle, trapezoidal
  std::vector<int> punctured_by_step_;                // needles punctured after each step
  int punctured_ = 0;
};

}  // namespace needlekit::insertion::detail
