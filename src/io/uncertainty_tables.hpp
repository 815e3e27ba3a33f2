// Internal to the io folder: reading the [uncertain], [sampling] and [[correlation]] tables of a file (an uncertainty
// file, or a design space with a robustness constraint), with errors that name FILE:LINE and the key.
#pragma once
#include <toml++/toml.h>

#include <string_view>
#include <vector>

#include "needlekit/uncertainty/design_uncertainty.hpp"

namespace needlekit::io::config {

struct UncertaintyTables {
  std::vector<uncertainty::DesignUncertainInput> inputs;  // in file order
  std::vector<uncertainty::Correlation> correlations;
  uncertainty::PropagationOptions sampling;
};

// `root` is the file's root table. A missing [uncertain] table is an error; [sampling] and [[correlation]] are
// optional.
UncertaintyTables read_uncertainty_tables(const toml::table& root, std::string_view file);

}  // namespace needlekit::io::config
