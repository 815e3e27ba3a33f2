// Internal to the io folder: reading the [uncertain], [sampling] and [[correlation]] tables of a file (an uncertainty
// file, or a design space with a robustness constraint), with errors that name FILE:LINE and the key.
#pragma once
#include <toml++/toml.h>

#include <functional>
#include <string_view>
#include <vector>

#include "needlekit/uncertainty/design_uncertainty.hpp"

namespace needlekit::io::config {

struct UncertaintyTables {
  std::vector<uncertainty::DesignUncertainInput> inputs;  // in file order
  std::vector<uncertainty::Correlation> correlations;
  uncertainty::PropagationOptions sampling;
};

// The dimension of an uncertain key; throws InvalidInput naming `what` for a key that is not an input.
using InputDimension = std::function<units::Dimension(std::string_view key, std::string_view what)>;
// design_inputs()'s.
units::Dimension design_input_dimension(std::string_view key, std::string_view what);

// `root` is the file's root table. A missing [uncertain] table is an error; [sampling] and [[correlation]] are
// optional.
UncertaintyTables read_uncertainty_tables(const toml::table& root, std::string_view file,
                                          const InputDimension& dimension_of = design_input_dimension);

// Rethrows an error of resolving the inputs (design_input_transform or the like) with FILE:LINE of the uncertain
// input it names (of the [uncertain] table when it names none).
[[noreturn]] void rethrow_at_input(const InvalidInput& error, const toml::table& root, std::string_view file,
                                   const std::vector<uncertainty::DesignUncertainInput>& inputs);

}  // namespace needlekit::io::config
