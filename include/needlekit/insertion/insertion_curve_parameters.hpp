// insertion::InsertionCurveOptions' parameter table (core/parameter.hpp): one row per field, declared here once; the
// defaults are the struct's initializers (insertion_curve.hpp). Insertion case files write them in [post_puncture]
// (`needlekit insert`). The insertion case reader, `needlekit insert --help`, `needlekit describe`,
// docs/reference.md, the validation in insertion_curve() and Python's InsertionCurveOptions read this table.
//
// A new parameter: its field with its initializer in InsertionCurveOptions, and one row here.
#pragma once
#include <tuple>

#include "needlekit/core/limits.hpp"
#include "needlekit/core/parameter.hpp"
#include "needlekit/insertion/insertion_curve.hpp"

namespace needlekit::insertion {

inline constexpr std::tuple kInsertionCurveParameters{
    Parameter<InsertionCurveOptions, double>{"final_depth", &InsertionCurveOptions::final_depth, 0, kNoLimit,
                                             Bound::Open, Bound::Open,
                                             "displacement of the needles' base at the end of the curve",
                                             "post_puncture", units::Dimension::Length, "", true},
    Parameter<InsertionCurveOptions, int>{"samples", &InsertionCurveOptions::cutting_samples, 1,
                                          limits::kMaxCurveSamples, Bound::Closed, Bound::Closed,
                                          "equally spaced samples of the cutting phase, from the first puncture to "
                                          "final_depth",
                                          "post_puncture", units::Dimension::Dimensionless, "cutting_samples"},
};
static_assert(field_count<InsertionCurveOptions>() == std::tuple_size_v<decltype(kInsertionCurveParameters)>,
              "a field of InsertionCurveOptions has no row in kInsertionCurveParameters (or a row too many)");

}  // namespace needlekit::insertion
