// The parameter tables of insertion::PostPunctureOptions and PostPunctureFitOptions (core/parameter.hpp): one row
// per field that a row can express, declared here once; the defaults are the structs' initializers
// (post_puncture_force.hpp). Insertion case files write the rows of group "post_puncture" in [post_puncture]
// (`needlekit insert`); tip_tolerance and fit_stiffness are set from Python only. The insertion case reader,
// `needlekit insert --help`, `needlekit describe`, docs/reference.md, the validation in post_puncture_loads and
// Python's PostPunctureOptions and PostPunctureFitOptions read these tables; tests/unit/test_parameter_tables.cpp
// checks that every field has a row or is listed below.
//
// A new parameter: its field with its initializer in the struct, and one row here.
#pragma once
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"

namespace needlekit::insertion {

inline constexpr std::tuple kPostPunctureParameters{
    // [post_puncture], in the order the reader has always listed them
    Parameter<PostPunctureOptions, double>{"reference_radius", &PostPunctureOptions::reference_radius, 0, kNoLimit,
                                           Bound::Closed, Bound::Open,
                                           "R of the beta load p = K*S*delta/R (0: the needle's largest distance "
                                           "from the channel axis)",
                                           "post_puncture", units::Dimension::Length},
    Parameter<PostPunctureOptions, double>{"max_edge_fraction", &PostPunctureOptions::max_edge_fraction, 0, 1,
                                           Bound::Closed, Bound::Closed,
                                           "loaded triangles with an edge longer than this fraction of the needle's "
                                           "length are bisected before Algorithm 3.1 (0: the mesh as it is)",
                                           "post_puncture"},
    Flag<PostPunctureOptions>{"cap_at_cutting_pressure", &PostPunctureOptions::cap_at_cutting_pressure,
                              "cap the beta load at the cutting pressure K*S (delta/R <= 1)", "post_puncture"},
    Flag<PostPunctureOptions>{"axial_component", &PostPunctureOptions::axial_component,
                              "sum the loads' components along the insertion direction (false: the load volumes, "
                              "Eq 3.20)",
                              "post_puncture"},
    // set from Python only
    Parameter<PostPunctureOptions, double>{"tip_tolerance", &PostPunctureOptions::tip_tolerance, 0, 1e-2,
                                           Bound::Closed, Bound::Closed,
                                           "vertices this close to the foremost point, relative to the needle's "
                                           "length, are on the tip and carry no beta load (Algorithm 3.1)"},
};
// Fields that are not parameters: axis_point (a point, NaN: the centroid of the tip vertices), set from Python only.
inline constexpr std::size_t kPostPuncturePointFields = 1;
static_assert(field_count<PostPunctureOptions>() ==
                  std::tuple_size_v<decltype(kPostPunctureParameters)> + kPostPuncturePointFields,
              "a field of PostPunctureOptions has no row in kPostPunctureParameters (or a row too many)");

// K and S of Eq 3.18 (PostPunctureFitOptions), [post_puncture] stiffness and scale; fit_stiffness is set from Python
// only (`needlekit insert` fits S to a measured curve).
inline constexpr std::tuple kPostPunctureFitParameters{
    Parameter<PostPunctureFitOptions, double>{"stiffness", &PostPunctureFitOptions::stiffness, 0, kNoLimit,
                                              Bound::Open, Bound::Open,
                                              "K of Eq 3.18, the tissue's cutting stiffness (fixed when fitting S)",
                                              "post_puncture", units::Dimension::Pressure, "", true},
    Parameter<PostPunctureFitOptions, double>{"scale", &PostPunctureFitOptions::scale, 0, kNoLimit, Bound::Open,
                                              Bound::Open, "S of Eq 3.18 (fixed when fitting K)", "post_puncture",
                                              units::Dimension::Dimensionless, "", true},
    Flag<PostPunctureFitOptions>{"fit_stiffness", &PostPunctureFitOptions::fit_stiffness,
                                 "fit K to a measured curve instead of S (only K*S is identifiable)"},
};
static_assert(field_count<PostPunctureFitOptions>() == std::tuple_size_v<decltype(kPostPunctureFitParameters)>,
              "a field of PostPunctureFitOptions has no row in kPostPunctureFitParameters (or a row too many)");

}  // namespace needlekit::insertion
