// Uncertainty files (`needlekit uncertainty UQ.toml`), in TOML: a design file (io/design_config.hpp) plus
//   [uncertain]   one inline table per uncertain input, keyed by the design-file key (uncertainty::design_inputs()):
//                 "needle.tip_diameter" = { distribution = "normal", mean = "30 um", sd = "2 um" }
//                 "tissue.alpha" = { distribution = "lognormal", median = "0.0183 N", sigma_log = 0.2 }
//                 distribution = normal (mean, sd) | truncated-normal (mean, sd, min, max) | lognormal (median,
//                 sigma_log) | uniform (min, max) | triangular (min, max, mode); every value but sigma_log carries
//                 the input's unit; an omitted mean (normal, truncated-normal), median (lognormal) or mode
//                 (triangular) is the design's nominal value.
//   [sampling]    samples = 4096 (>= 2), method = "sobol" | "monte-carlo", seed = 1 (integer >= 0),
//                 sobol_indices = true (Saltelli design, N·(k+2) runs)   (optional table)
//   [[correlation]]  inputs = ["tissue.alpha", "tissue.tau"], rho = 0.5   (optional, any number; normal scores)
// Errors name FILE:LINE and the key: an unknown key or distribution, a negative sd, min >= max, an input the
// design does not have, a distribution with more than 0.1 % of its mass outside the input's physical range.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/io/design_config.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

namespace needlekit::io {

struct UncertaintyFile {
  uncertainty::DesignCase design;
  std::vector<uncertainty::DesignUncertainInput> inputs;  // in file order
  std::vector<uncertainty::Correlation> correlations;
  uncertainty::PropagationOptions sampling;
};

// What a UQ file's base is: a design file, a patch case ([surface]: io/patch_uncertainty_config.hpp) or an FE case
// (case = "indent_....toml": io/fe_uncertainty_config.hpp). Throws IoError for an unreadable file or bad TOML.
enum class UncertaintyFileKind { Design, Patch, FeCase };
UncertaintyFileKind uncertainty_file_kind(const std::filesystem::path& path);

// Throws IoError (unreadable file, TOML syntax) or InvalidInput.
UncertaintyFile read_uncertainty_file(const std::filesystem::path& path);
UncertaintyFile parse_uncertainty_toml(std::string_view text, std::string_view source_name);

}  // namespace needlekit::io
