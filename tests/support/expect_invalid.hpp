// Asserting that a call throws needlekit::InvalidInput whose message contains a fragment.
#pragma once
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "needlekit/core/errors.hpp"

namespace needlekit::test {

template <typename F>
void expect_invalid(F&& f, const std::string& fragment) {
  try {
    f();
    FAIL() << "expected InvalidInput containing '" << fragment << "'";
  } catch (const InvalidInput& error) {
    EXPECT_THAT(error.what(), testing::HasSubstr(fragment));
  }
}

}  // namespace needlekit::test
