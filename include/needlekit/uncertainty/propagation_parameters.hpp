// uncertainty::PropagationOptions' parameter table (core/parameter.hpp): one row per field but the progress callback,
// declared here once; the defaults are the struct's initializers (propagation.hpp). Uncertainty files write the rows
// of group "sampling" in [sampling]; threads is set by the CLI's --threads and from Python only. The [sampling]
// reader, `needlekit uncertainty --help`, `needlekit describe`, docs/reference.md, the validation in propagate() and
// Python's PropagationOptions read this table; tests/unit/test_parameter_tables.cpp checks that every field has a row.
//
// A new parameter: its field with its initializer in PropagationOptions, and one row here.
#pragma once
#include <cstddef>
#include <cstdint>
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/uncertainty/propagation.hpp"

namespace needlekit::uncertainty {

inline constexpr std::size_t kPropagationCallbackFields = 1;  // progress

inline constexpr std::tuple kPropagationParameters{
    // The upper end is a work limit: every sample is a model run (or k + 2 of them with sobol_indices).
    Parameter<PropagationOptions, std::size_t>{"samples", &PropagationOptions::samples, 2, 1e8, Bound::Closed,
                                               Bound::Closed,
                                               "N, the rows of the sample matrix A (sobol works best with N = 2^m)",
                                               "sampling"},
    Choice<PropagationOptions, SamplingMethod, 2>{"method", &PropagationOptions::method, &kSamplingMethodNames,
                                                  "how the sample points are drawn", "sampling"},
    Parameter<PropagationOptions, std::uint64_t>{"seed", &PropagationOptions::seed, 0, kNoLimit, Bound::Closed,
                                                 Bound::Closed,
                                                 "the same seed gives the same numbers on any thread count",
                                                 "sampling"},
    Flag<PropagationOptions>{"sobol_indices", &PropagationOptions::sobol_indices,
                             "also run B and AB_i for Sobol' indices: N (k + 2) evaluations for k inputs instead of N",
                             "sampling"},
    Parameter<PropagationOptions, int>{"threads", &PropagationOptions::threads, 0, kNoLimit, Bound::Closed,
                                       Bound::Closed, "threads (0: all hardware threads)"},
    Parameter<PropagationOptions, int>{"histogram_bins", &PropagationOptions::histogram_bins, 1, kNoLimit,
                                       Bound::Closed, Bound::Closed,
                                       "bins of each continuous output's histogram, over its [min, max]", "sampling"},
};
static_assert(field_count<PropagationOptions>() ==
                  std::tuple_size_v<decltype(kPropagationParameters)> + kPropagationCallbackFields,
              "every field of uncertainty::PropagationOptions but the callback has a row");

}  // namespace needlekit::uncertainty
