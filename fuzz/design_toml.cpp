// Design files (`evaluate`, `sweep`).
#include "fuzz_target.hpp"
#include "needlekit/io/design_config.hpp"

NEEDLEKIT_FUZZ_TARGET(design_toml) {
  needlekit::fuzz::refusals_allowed([&] { needlekit::io::parse_design_toml(bytes, "fuzz.toml"); });
}
