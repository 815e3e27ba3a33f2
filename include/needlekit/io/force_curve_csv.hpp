// Force-depth curves as CSV: the first column is the depth, the second the force, each header naming its unit
// (depth_um | depth_mm | depth_m, force_N | force_mN | force_uN); further columns are ignored. This is the format
// that `needlekit indent --out` writes (NAME_force_depth.csv), so measured and simulated curves read alike.
#pragma once
#include <filesystem>
#include <string_view>

#include "needlekit/insertion/force_curve.hpp"

namespace needlekit::io {

// Throws IoError (unreadable file) or InvalidInput naming FILE:LINE (a header without a known unit, a value that is
// not a number, depths that do not increase strictly, fewer than two rows).
insertion::ForceDepthCurve read_force_curve_csv(const std::filesystem::path& path);
insertion::ForceDepthCurve parse_force_curve_csv(std::string_view text, std::string_view source_name);

}  // namespace needlekit::io
