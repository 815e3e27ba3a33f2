// Measured force-depth curves (CSV: `insert` [post_puncture] measured, [pre_puncture] curve, toughness_from).
#include "fuzz_target.hpp"
#include "needlekit/io/force_curve_csv.hpp"

NEEDLEKIT_FUZZ_TARGET(force_curve_csv) {
  needlekit::fuzz::refusals_allowed([&] { needlekit::io::parse_force_curve_csv(bytes, "fuzz.csv"); });
}
