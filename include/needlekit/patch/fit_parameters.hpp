// The parameter tables (core/parameter.hpp) of patch::FitOptions and its two nested options, FlexibleFitOptions and
// EquilibriumFitOptions: one row per field that a row can express, declared here once; the defaults are the structs'
// initializers (fit_patch.hpp, flexible_fit.hpp, equilibrium_fit.hpp). Patch case files write the rows of group
// "patch" in [patch] (`needlekit patch`); the others are set from Python only. The patch case reader, `needlekit
// patch --help`, `needlekit describe`, docs/reference.md, the fits' validation and Python's FitOptions,
// FlexibleFitOptions and EquilibriumFitOptions read these tables; tests/unit/test_parameter_tables.cpp checks that
// every field has a row or is listed below. [patch]'s size, needles_per_row and spring_constant set PatchDesignOptions'
// fields in pairs and threes (width_u = width_v, ...) and are read by hand.
//
// A new parameter: its field with its initializer in its struct, and one row here.
#pragma once
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/patch/fit_patch.hpp"

namespace needlekit::patch {

inline constexpr std::tuple kFlexibleFitParameters{
    // [patch], kind = "flexible" only
    Parameter<FlexibleFitOptions, double>{"max_spring_energy", &FlexibleFitOptions::max_spring_energy, 0, kNoLimit,
                                          Bound::Open, Bound::Closed,
                                          "E_cri: the largest energy a spring may store (inf: the patch conforms "
                                          "completely; files of kind = \"flexible\" must give it)",
                                          "patch", units::Dimension::Energy},
    Choice<FlexibleFitOptions, FirstNode, 2>{"first_node", &FlexibleFitOptions::first_node, &kFirstNodeNames,
                                             "the node the flexible fit starts from (Alg 5.1)", "patch"},
    Choice<FlexibleFitOptions, WalkMethod, 2>{"walk", &FlexibleFitOptions::walk, &kWalkMethodNames,
                                              "how the traverse between nodes crosses triangle edges", "patch"},
    // set from Python only
    Parameter<FlexibleFitOptions, int>{"cap_samples", &FlexibleFitOptions::cap_samples, 2, 10000, Bound::Closed,
                                       Bound::Closed, "samples of lambda before bisection in the energy cap"},
};
// Fields that are not parameters: progress (a callback).
inline constexpr std::size_t kFlexibleFitCallbackFields = 1;
static_assert(field_count<FlexibleFitOptions>() ==
                  std::tuple_size_v<decltype(kFlexibleFitParameters)> + kFlexibleFitCallbackFields,
              "a field of FlexibleFitOptions has no row in kFlexibleFitParameters (or a row too many)");

inline constexpr std::tuple kEquilibriumFitParameters{
    // [patch], kind = "equilibrium" only
    Parameter<EquilibriumFitOptions, double>{"load", &EquilibriumFitOptions::node_load, 0, kNoLimit, Bound::Open,
                                             Bound::Open,
                                             "force pressing each node along the approach (files: default F(A) of "
                                             "the case's needle, Eq 4.2)",
                                             "patch", units::Dimension::Force, "node_load"},
    // set from Python only
    Parameter<EquilibriumFitOptions, double>{"contact_ratio", &EquilibriumFitOptions::contact_ratio, 0, kNoLimit,
                                             Bound::Open, Bound::Open,
                                             "contact penalty = contact_ratio times the largest spring constant"},
    Parameter<EquilibriumFitOptions, double>{"anchor_ratio", &EquilibriumFitOptions::anchor_ratio, 0, kNoLimit,
                                             Bound::Closed, Bound::Open,
                                             "tangential anchor stiffness per node = anchor_ratio times the largest "
                                             "spring constant (0: the patch may slide)"},
    Parameter<EquilibriumFitOptions, double>{"tolerance", &EquilibriumFitOptions::tolerance, 0, 1, Bound::Open,
                                             Bound::Open, "stop when the gradient's largest entry is below "
                                                          "tolerance times node_load"},
    Parameter<EquilibriumFitOptions, int>{"max_iterations", &EquilibriumFitOptions::max_iterations, 1, 100000,
                                          Bound::Closed, Bound::Closed,
                                          "Newton iterations (each moves a node by at most a quarter pitch)"},
};
// Fields that are not parameters: progress (a callback).
inline constexpr std::size_t kEquilibriumFitCallbackFields = 1;
static_assert(field_count<EquilibriumFitOptions>() ==
                  std::tuple_size_v<decltype(kEquilibriumFitParameters)> + kEquilibriumFitCallbackFields,
              "a field of EquilibriumFitOptions has no row in kEquilibriumFitParameters (or a row too many)");

inline constexpr std::tuple kFitParameters{
    Choice<FitOptions, PatchKind, 3>{"kind", &FitOptions::kind, &kPatchKindNames,
                                     "how the patch is fitted to the surface", "patch", "", true},
};
// Fields that are not parameters: flexible and equilibrium (the nested options, tabled above).
inline constexpr std::size_t kFitNestedFields = 2;
static_assert(field_count<FitOptions>() == std::tuple_size_v<decltype(kFitParameters)> + kFitNestedFields,
              "a field of FitOptions has no row in kFitParameters (or a row too many)");

}  // namespace needlekit::patch
