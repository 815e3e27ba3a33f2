// Patch uncertainty files (`needlekit uncertainty UQ.toml` where UQ.toml is a patch case): a patch case
// (io/patch_config.hpp) plus the [uncertain], [sampling] and [[correlation]] tables of io/uncertainty_config.hpp,
// with keys of uncertainty::patch_inputs():
//   "placement.offset_u" = { distribution = "uniform", min = "-2 mm", max = "2 mm" }   # along the patch axis U
//   "placement.offset_v" = { distribution = "normal", sd = "1 mm" }                    # mean 0
//   "placement.rotation" = { distribution = "normal", sd = "5 deg" }                   # mean surface.rotation
//   "tissue.alpha" = { distribution = "lognormal", sigma_log = 0.3 }                   # and the other design inputs
// Errors name FILE:LINE and the key, as for design uncertainty files.
#pragma once
#include <filesystem>
#include <string_view>
#include <vector>

#include "needlekit/io/patch_config.hpp"
#include "needlekit/uncertainty/patch_uncertainty.hpp"

namespace needlekit::io {

struct PatchUncertaintyFile {
  PatchCase patch;
  std::vector<uncertainty::DesignUncertainInput> inputs;  // in file order
  std::vector<uncertainty::Correlation> correlations;
  uncertainty::PropagationOptions sampling;
};

// Throws IoError (unreadable file, TOML syntax) or InvalidInput.
PatchUncertaintyFile read_patch_uncertainty_file(const std::filesystem::path& path);
PatchUncertaintyFile parse_patch_uncertainty_toml(std::string_view text, std::string_view source_name,
                                                  const std::filesystem::path& base_folder);

// The fit-and-evaluate options of a patch case (as `needlekit patch` uses them, without spring geodesics).
patch::FitAndEvaluateOptions fit_and_evaluate_options(const PatchCase& c);

}  // namespace needlekit::io
