// uncertainty::FeSurrogateOptions' parameter table (core/parameter.hpp): one row per field but the nested sampling
// (kPropagationParameters) and the progress callback, declared here once; the defaults are the struct's initializers
// (fe_surrogate.hpp). FE uncertainty files write them in [surrogate]. The reader, `needlekit uncertainty --help`,
// `needlekit describe`, docs/reference.md, the validation in fe_surrogate() and Python's FeSurrogateOptions read this
// table; tests/unit/test_parameter_tables.cpp checks that every field has a row or is counted below.
//
// A new parameter: its field with its initializer in FeSurrogateOptions, and one row here.
#pragma once
#include <cstddef>
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/uncertainty/fe_surrogate.hpp"

namespace needlekit::uncertainty {

inline constexpr std::tuple kFeSurrogateParameters{
    Parameter<FeSurrogateOptions, int>{"design_runs", &FeSurrogateOptions::design_runs, 0, kNoLimit, Bound::Closed,
                                       Bound::Closed,
                                       "FE runs of the fit, at least the polynomial's terms (0: twice the terms)",
                                       "surrogate"},
    Parameter<FeSurrogateOptions, int>{"validation_runs", &FeSurrogateOptions::validation_runs, 1, kNoLimit,
                                       Bound::Closed, Bound::Closed, "held-out FE runs that measure the fit's error",
                                       "surrogate"},
    OptionalQuantity<FeSurrogateOptions>{"depth_limit", &FeSurrogateOptions::depth_limit, 0, kNoLimit, Bound::Open,
                                         Bound::Open,
                                         "X of P(puncture before X) (not given: the case's loading depth)",
                                         "surrogate", units::Dimension::Length},
};
// Fields that are not rows: sampling (its own table, kPropagationParameters) and the progress callback.
inline constexpr std::size_t kFeSurrogateOtherFields = 2;
static_assert(field_count<FeSurrogateOptions>() ==
                  std::tuple_size_v<decltype(kFeSurrogateParameters)> + kFeSurrogateOtherFields,
              "a field of FeSurrogateOptions has no row (or a row too many)");

}  // namespace needlekit::uncertainty
