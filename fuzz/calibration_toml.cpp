// Calibration files (`calibrate`), read against the examples folder so that their case and curve paths resolve.
#include "fuzz_target.hpp"
#include "needlekit/calibration/calibration_problem.hpp"

NEEDLEKIT_FUZZ_TARGET(calibration_toml) {
  needlekit::fuzz::refusals_allowed(
      [&] { needlekit::calibration::parse_calibration_toml(bytes, "fuzz.toml", NEEDLEKIT_FUZZ_EXAMPLES_DIR); });
}
