// Insertion case files (`insert`): [post_puncture] and [pre_puncture], then the indentation part as `insert` reads it.
#include "fuzz_target.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/insertion_case.hpp"

NEEDLEKIT_FUZZ_TARGET(insertion_case_toml) {
  needlekit::fuzz::refusals_allowed([&] {
    const auto settings = needlekit::io::parse_insertion_settings(bytes, "fuzz.toml", "/nonexistent-needlekit-fuzz");
    needlekit::io::parse_indentation_case_toml(settings.indentation_text, "fuzz.toml", "/nonexistent-needlekit-fuzz");
  });
}
