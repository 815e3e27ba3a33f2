// patch::PatchDesignOptions' parameter table (core/parameter.hpp): one row per number, declared here once; the
// defaults are the struct's initializers (patch_design.hpp). The rows belong to no file table: a patch case's [patch]
// writes them as shorthands that set two or three at once (size: width_u and width_v; needles_per_row: needles_u and
// needles_v; spring_constant: the three stiffnesses, or a table {u, v, diagonal}), read in io's patch reader.
// The validation in patch_design(), `needlekit describe`, docs/reference.md and Python's PatchDesignOptions read
// this table; tests/unit/test_parameter_tables.cpp checks that every field has a row or is counted below.
//
// A new parameter: its field with its initializer in PatchDesignOptions, and one row here.
#pragma once
#include <cstddef>
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/patch/patch_design.hpp"

namespace needlekit::patch {

inline constexpr std::tuple kPatchDesignParameters{
    Parameter<PatchDesignOptions, int>{"needles_u", &PatchDesignOptions::needles_u, 2, 10000, Bound::Closed,
                                       Bound::Closed, "n_h, needles (= nodes) along U ([patch] needles_per_row)"},
    Parameter<PatchDesignOptions, int>{"needles_v", &PatchDesignOptions::needles_v, 2, 10000, Bound::Closed,
                                       Bound::Closed, "n_v, needles along V ([patch] needles_per_row)"},
    Parameter<PatchDesignOptions, double>{"width_u", &PatchDesignOptions::width_u, 0, kNoLimit, Bound::Open,
                                          Bound::Open,
                                          "patch side w along U; node pitch w/n (Eq 4.25), nodes at the cells' "
                                          "centres ([patch] size)",
                                          "", units::Dimension::Length},
    Parameter<PatchDesignOptions, double>{"width_v", &PatchDesignOptions::width_v, 0, kNoLimit, Bound::Open,
                                          Bound::Open, "patch side along V ([patch] size)", "",
                                          units::Dimension::Length},
    Parameter<PatchDesignOptions, double>{"stiffness_u", &PatchDesignOptions::stiffness_u, 0, kNoLimit, Bound::Open,
                                          Bound::Open, "spring constant along U (§6.4: 1 N/mm; [patch] spring_constant)",
                                          "", units::Dimension::Stiffness},
    Parameter<PatchDesignOptions, double>{"stiffness_v", &PatchDesignOptions::stiffness_v, 0, kNoLimit, Bound::Open,
                                          Bound::Open, "spring constant along V ([patch] spring_constant)", "",
                                          units::Dimension::Stiffness},
    Parameter<PatchDesignOptions, double>{"stiffness_diagonal", &PatchDesignOptions::stiffness_diagonal, 0, kNoLimit,
                                          Bound::Open, Bound::Open,
                                          "spring constant of both diagonals ([patch] spring_constant)", "",
                                          units::Dimension::Stiffness},
};
// Fields that are not rows: needle and material (validated by their own folders).
inline constexpr std::size_t kPatchDesignOtherFields = 2;
static_assert(field_count<PatchDesignOptions>() ==
                  std::tuple_size_v<decltype(kPatchDesignParameters)> + kPatchDesignOtherFields,
              "a field of PatchDesignOptions has no row (or a row too many)");

}  // namespace needlekit::patch
