// FE uncertainty files (`needlekit uncertainty UQ.toml` where UQ.toml names an indentation case): the FE surrogate
// of uncertainty/fe_surrogate.hpp.
//   case = "indent_coarse_two_layers.toml"   an indentation case file (`needlekit indent --help`), relative to this
//                                            file; its [puncture] critical_pressure is the nominal P_c
//   [uncertain]   keys tissue.layers.N.youngs_modulus (N = 0: top layer) and puncture.critical_pressure, as in
//                 io/uncertainty_config.hpp (an omitted median/mean is the case's value)
//   [sampling], [[correlation]]   as in io/uncertainty_config.hpp (the sampling of the surrogate)
//   [surrogate]   design_runs = 0 (FE runs of the fit; 0: twice the polynomial's terms), validation_runs = 4 (>= 1),
//                 depth_limit = "100 um" (X of P(puncture before X); default: the case's loading depth)  (optional)
// Errors name FILE:LINE and the key.
#pragma once
#include <filesystem>
#include <string_view>
#include <vector>

#include "needlekit/uncertainty/fe_surrogate.hpp"

namespace needlekit::io {

struct FeUncertaintyFile {
  std::filesystem::path case_path;             // resolved against the file's folder
  insertion::IndentationCase indentation;
  std::vector<uncertainty::DesignUncertainInput> inputs;  // in file order
  std::vector<uncertainty::Correlation> correlations;
  uncertainty::FeSurrogateOptions options;     // sampling, design_runs, validation_runs, depth_limit
};

// Throws IoError (unreadable file, TOML syntax) or InvalidInput.
FeUncertaintyFile read_fe_uncertainty_file(const std::filesystem::path& path);
FeUncertaintyFile parse_fe_uncertainty_toml(std::string_view text, std::string_view source_name,
                                            const std::filesystem::path& base_folder);

}  // namespace needlekit::io
