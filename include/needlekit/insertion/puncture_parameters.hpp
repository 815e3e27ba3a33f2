// insertion::PunctureOptions' parameter table (core/parameter.hpp): one row per field, declared here once, written in
// a case file's [puncture] (critical_pressure and toughness are optional quantities: not given, their criterion is not
// used). validate(PunctureOptions), the case reader, `needlekit describe`, docs/reference.md and Python's PunctureOptions read it; tests/unit/test_parameter_tables.cpp checks that every field
// has a row.
//
// A new parameter: its field with its initializer in PunctureOptions, and one row here.
#pragma once
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/insertion/puncture_criteria.hpp"

namespace needlekit::insertion {

inline constexpr std::tuple kPunctureParameters{
    Choice<PunctureOptions, PunctureLaw, 2>{"criterion", &PunctureOptions::criterion, &kPunctureLawNames,
                                            "the law that decides the puncture", "puncture"},
    Parameter<PunctureOptions, double>{"material_length", &PunctureOptions::material_length, 0, kNoLimit,
                                       Bound::Open, Bound::Open,
                                       "averaged-pressure: the radius l of the disc the contact pressure is averaged "
                                       "over (a property of the tissue)",
                                       "puncture", units::Dimension::Length},
    OptionalQuantity<PunctureOptions>{"critical_pressure", &PunctureOptions::critical_pressure, 0, kNoLimit,
                                      Bound::Open, Bound::Open,
                                      "P_c: the contact pressure F/A at which the needle punctures (Eq 3.17), or "
                                      "the averaged contact pressure of the averaged-pressure law (not given: the "
                                      "criterion is not used)",
                                      "puncture", units::Dimension::Pressure},
    OptionalQuantity<PunctureOptions>{"toughness", &PunctureOptions::toughness, 0, kNoLimit, Bound::Open,
                                      Bound::Open,
                                      "J: the fracture energy per crack area of the fracture-energy criterion "
                                      "(J/m2 = N/m; not given: the criterion is not used, or toughness_from)",
                                      "puncture", units::Dimension::Stiffness},
};
static_assert(field_count<PunctureOptions>() == std::tuple_size_v<decltype(kPunctureParameters)>,
              "a field of PunctureOptions has no row in kPunctureParameters (or a row too many)");

}  // namespace needlekit::insertion
