// Uncertainty files (`uncertainty`): the same bytes as a design, a patch and an FE case, the three forms the command
// reads. FE cases resolve their indentation case in the examples folder; patch cases find no body mesh (reading
// meshes is the surface targets' work).
#include "fuzz_target.hpp"
#include "needlekit/io/fe_uncertainty_config.hpp"
#include "needlekit/io/patch_uncertainty_config.hpp"
#include "needlekit/io/uncertainty_config.hpp"

NEEDLEKIT_FUZZ_TARGET(uncertainty_toml) {
  using namespace needlekit::io;
  needlekit::fuzz::refusals_allowed([&] { parse_uncertainty_toml(bytes, "fuzz.toml"); });
  needlekit::fuzz::refusals_allowed(
      [&] { parse_patch_uncertainty_toml(bytes, "fuzz.toml", "/nonexistent-needlekit-fuzz"); });
  needlekit::fuzz::refusals_allowed(
      [&] { parse_fe_uncertainty_toml(bytes, "fuzz.toml", NEEDLEKIT_FUZZ_EXAMPLES_DIR); });
}
