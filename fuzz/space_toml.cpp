// Design-space files (`optimize`).
#include "fuzz_target.hpp"
#include "needlekit/io/design_config.hpp"

NEEDLEKIT_FUZZ_TARGET(space_toml) {
  needlekit::fuzz::refusals_allowed([&] { needlekit::io::parse_space_toml(bytes, "fuzz.toml"); });
}
