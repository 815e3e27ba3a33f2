// One fuzz target = one reader fed arbitrary bytes. A target returns normally when the reader accepts the input or
// refuses it with needlekit's InvalidInput / IoError; anything else (a crash, a sanitizer report, another exception
// such as std::bad_alloc, a hang) is a finding.
//
// NEEDLEKIT_FUZZ_TARGET(name) { ... } defines the body once. Built with libFuzzer (NEEDLEKIT_LIBFUZZER, clang
// -fsanitize=fuzzer) it is the executable's LLVMFuzzerTestOneInput; in the ordinary build it registers itself with
// needlekit_fuzz_replay, which ctest runs over the seed corpus and every input that ever crashed
// (tests/data/fuzz-regressions/<name>/), so no clang is needed to keep them fixed.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "needlekit/core/errors.hpp"

namespace needlekit::fuzz {

using TargetFunction = void (*)(std::string_view bytes);
// Registers a target for the replay driver; returns true.
bool register_target(std::string_view name, TargetFunction function);

// Runs `read` and swallows the two exceptions that mean "input refused with a message".
template <class Read>
void refusals_allowed(Read&& read) {
  try {
    read();
  } catch (const InvalidInput&) {
  } catch (const IoError&) {
  }
}

}  // namespace needlekit::fuzz

#ifdef NEEDLEKIT_LIBFUZZER
#define NEEDLEKIT_FUZZ_ENTRY(name)                                                                      \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {                   \
    name##_target(std::string_view(reinterpret_cast<const char*>(data), size));                          \
    return 0;                                                                                            \
  }
#else
#define NEEDLEKIT_FUZZ_ENTRY(name) \
  [[maybe_unused]] static const bool name##_registered = needlekit::fuzz::register_target(#name, &name##_target);
#endif

#define NEEDLEKIT_FUZZ_TARGET(name)                \
  static void name##_target(std::string_view bytes); \
  NEEDLEKIT_FUZZ_ENTRY(name)                       \
  static void name##_target(std::string_view bytes)
