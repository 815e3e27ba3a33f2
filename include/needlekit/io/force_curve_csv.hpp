// Force-depth curves as CSV: reading a measured (or previously computed) curve, for fitting the post-puncture scale
// S (insertion/post_puncture_force.hpp), as the pre-puncture part of an insertion, or for the two-insertion
// toughness of Eq 3.16 (io/indentation_case.hpp). `needlekit indent --out` writes this format (NAME_force_depth.csv),
// so measured and simulated curves read alike.
//
// Format: a header line naming a depth column `depth_<unit>` (unit nm, um, mm, cm or m) and a force column
// `force_<unit>` (uN, mN or N), in any order among other columns (ignored); then one row per sample, depths
// strictly increasing. Blank lines and lines starting with '#' are skipped.
#pragma once
#include <filesystem>
#include <string_view>

#include "needlekit/insertion/force_curve.hpp"

namespace needlekit::io {

// Throws IoError when the file cannot be read, InvalidInput naming FILE:LINE and the column for a missing column,
// a non-numeric value, a non-monotonic depth or an empty curve. Returns SI (m, N).
insertion::ForceDepthCurve read_force_curve_csv(const std::filesystem::path& path);
insertion::ForceDepthCurve parse_force_curve_csv(std::string_view text, std::string_view source_name);

}  // namespace needlekit::io
