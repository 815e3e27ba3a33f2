// insertion::TriangleClassificationOptions' parameter table (core/parameter.hpp): one row per field that a row can
// express, declared here once; the defaults are the struct's initializers (triangle_classification.hpp). Insertion
// case files write the rows of group "post_puncture" in [post_puncture] (`needlekit insert`); bore_radius (0: from
// the case's parametric needle) and the two vectors are set from Python only. The insertion case reader,
// `needlekit insert --help`, `needlekit describe`, docs/reference.md, the validation in classify_triangles and
// Python's TriangleClassificationOptions read this table.
//
// A new parameter: its field with its initializer in TriangleClassificationOptions, and one row here.
#pragma once
#include <numbers>
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/insertion/triangle_classification.hpp"

namespace needlekit::insertion {

inline constexpr std::tuple kTriangleClassificationParameters{
    Parameter<TriangleClassificationOptions, double>{
        "side_tolerance", &TriangleClassificationOptions::side_tolerance, 0, std::numbers::pi / 4, Bound::Closed,
        Bound::Closed,
        "a triangle is a side triangle (group 1) when its normal is within this angle of perpendicular to the "
        "insertion direction",
        "post_puncture", units::Dimension::Angle},
    Parameter<TriangleClassificationOptions, double>{
        "alpha_tolerance", &TriangleClassificationOptions::alpha_tolerance, 0, std::numbers::pi / 4, Bound::Closed,
        Bound::Closed, "a group-2 triangle is alpha when its normal is within this angle of the insertion direction",
        "post_puncture", units::Dimension::Angle},
    Parameter<TriangleClassificationOptions, double>{
        "bore_radius", &TriangleClassificationOptions::bore_radius, 0, kNoLimit, Bound::Closed, Bound::Open,
        "radius of the needle's channel about its axis for the channel test without a surface mesh (0: the "
        "visibility test decides)",
        "", units::Dimension::Length},
    Flag<TriangleClassificationOptions>{"occlusion_test", &TriangleClassificationOptions::occlusion_test,
                                        "the occlusion test for jagged needles (§3.6.1)", "post_puncture"},
};
// Fields that are not parameters: insertion_direction and axis_point (vectors), set from Python only.
inline constexpr std::size_t kTriangleClassificationVectorFields = 2;
static_assert(field_count<TriangleClassificationOptions>() ==
                  std::tuple_size_v<decltype(kTriangleClassificationParameters)> +
                      kTriangleClassificationVectorFields,
              "a field of TriangleClassificationOptions has no row (or a row too many)");

}  // namespace needlekit::insertion
