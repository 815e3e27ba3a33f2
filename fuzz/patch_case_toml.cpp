// Patch case files (`patch`).
#include "fuzz_target.hpp"
#include "needlekit/io/patch_config.hpp"

NEEDLEKIT_FUZZ_TARGET(patch_case_toml) {
  needlekit::fuzz::refusals_allowed(
      [&] { needlekit::io::parse_patch_case_toml(bytes, "fuzz.toml", "/nonexistent-needlekit-fuzz"); });
}
