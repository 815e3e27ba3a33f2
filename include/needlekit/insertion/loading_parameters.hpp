// insertion::Loading's parameter table (core/parameter.hpp): one row per field, declared here once; the defaults are
// the struct's initializers (indentation.hpp). Case files write them in [loading] (`needlekit indent`; `needlekit
// insert` reads the same table). The case reader, `needlekit indent --help`, `needlekit describe`,
// docs/reference.md and Python's IndentationCase read this table; tests/unit/test_parameter_tables.cpp checks that
// every field has a row. insertion::validate checks the same ranges with the case's context (the block's height,
// the contact model).
//
// A new parameter: its field with its initializer in Loading, and one row here.
#pragma once
#include <numbers>
#include <tuple>

#include "needlekit/core/limits.hpp"
#include "needlekit/core/parameter.hpp"
#include "needlekit/insertion/indentation.hpp"

namespace needlekit::insertion {

inline constexpr std::tuple kLoadingParameters{
    Parameter<Loading, double>{"depth", &Loading::depth, 0, kNoLimit, Bound::Open, Bound::Open,
                               "final depth of the tip below the undeformed surface (along the needle's axis when it "
                               "is tilted)",
                               "loading", units::Dimension::Length, "", true},
    Parameter<Loading, double>{"angle", &Loading::angle, 0, std::numbers::pi / 2, Bound::Closed, Bound::Open,
                               "the needle's axis from the skin's normal (surface contact only)", "loading",
                               units::Dimension::Angle},
    Parameter<Loading, double>{"azimuth", &Loading::azimuth, -kNoLimit, kNoLimit, Bound::Open, Bound::Open,
                               "the tilt's direction in the block's x-y plane from +x (a bevel's face normal turns "
                               "towards it)",
                               "loading", units::Dimension::Angle},
    Parameter<Loading, int>{"steps", &Loading::steps, 1, limits::kMaxLoadSteps, Bound::Closed, Bound::Closed,
                            "equal load steps from 0 to the depth", "loading"},
    Flag<Loading>{"continue_after_puncture", &Loading::stop_at_puncture,
                  "go on to the final depth after the puncture point", "loading", "stop_at_puncture", true},
};
static_assert(field_count<Loading>() == std::tuple_size_v<decltype(kLoadingParameters)>,
              "a field of Loading has no row in kLoadingParameters (or a row too many)");

}  // namespace needlekit::insertion
