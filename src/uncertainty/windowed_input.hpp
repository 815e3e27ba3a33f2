// Internal to the uncertainty folder: one uncertain input with its physical window, checked as the docs say (more
// than kMaxTruncatedMass outside the window is refused, a smaller mass is truncated and noted). Shared by the design
// and the patch studies.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/units.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

namespace needlekit::uncertainty::detail {

struct InputRange {
  units::Dimension dimension;
  std::string_view unit;       // of messages
  double lower, upper;         // SI
  std::string_view meaning;
};

// `nominal` centres the distribution when input.centred_on_nominal. Throws InvalidInput naming `what`.
UncertainInput windowed_input(const DesignUncertainInput& input, double nominal, const InputRange& range,
                              std::string_view what, std::vector<std::string>& notes);

// The transform of the resolved inputs, with the note on correlated inputs' Sobol' indices when it is correlated.
InputTransform noted_transform(std::vector<UncertainInput> inputs, const std::vector<Correlation>& correlations,
                               std::vector<std::string>& notes);

}  // namespace needlekit::uncertainty::detail
