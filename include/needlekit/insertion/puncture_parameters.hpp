// insertion::PunctureOptions' parameter table (core/parameter.hpp): one row per field that a row can express, declared
// here once, written in a case file's [puncture]. validate(PunctureOptions), the case reader, `needlekit describe`,
// docs/reference.md and Python's PunctureOptions read it; tests/unit/test_parameter_tables.cpp checks that every field
// has a row or is listed below.
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
};
// Fields that are not rows: critical_pressure and toughness, optional quantities (unset: the criterion is not used),
// which core/parameter.hpp's rows cannot hold yet; the case reader reads them as optional positive quantities.
inline constexpr std::size_t kPunctureOptionalFields = 2;
static_assert(field_count<PunctureOptions>() ==
                  std::tuple_size_v<decltype(kPunctureParameters)> + kPunctureOptionalFields,
              "a field of PunctureOptions has no row in kPunctureParameters (or a row too many)");

}  // namespace needlekit::insertion
