// Tissue case files (`tissue-mesh`; the [tissue] and [mesh] tables of indentation and insertion cases).
#include "fuzz_target.hpp"
#include "needlekit/io/tissue_config.hpp"

NEEDLEKIT_FUZZ_TARGET(tissue_case_toml) {
  needlekit::fuzz::refusals_allowed(
      [&] { needlekit::io::parse_tissue_case_toml(bytes, "fuzz.toml", "/nonexistent-needlekit-fuzz"); });
}
