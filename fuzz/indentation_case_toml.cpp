// Indentation case files (`indent`), with their [tissue] and [mesh] tables. Relative file names resolve against a
// folder that does not exist, so a case naming a needle STL or a .msh is refused as unreadable.
#include "fuzz_target.hpp"
#include "needlekit/io/indentation_case.hpp"

NEEDLEKIT_FUZZ_TARGET(indentation_case_toml) {
  needlekit::fuzz::refusals_allowed(
      [&] { needlekit::io::parse_indentation_case_toml(bytes, "fuzz.toml", "/nonexistent-needlekit-fuzz"); });
}
