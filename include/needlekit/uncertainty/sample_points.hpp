// Uniform points in (0, 1)^s for sampling: pseudo-random (Monte Carlo) or scrambled Sobol' (randomised quasi-Monte
// Carlo). Points are addressed by (group, block): the rows of one block depend only on the seed, the group and the
// block index, never on which thread makes them or in which order, so a study gives the same numbers on any
// number of threads.
//  - monte-carlo: std::mt19937_64 seeded per block from SplitMix64 of (seed, group, block) (Steele, Lea & Flood,
//    OOPSLA 2014), 53-bit uniforms shifted by half an ulp into (0, 1).
//  - sobol: Boost.Random's Sobol' sequence (Joe & Kuo direction numbers, Bratley & Fox TOMS 1988) with the origin
//    as row 0, each dimension scrambled by the hash-based nested uniform (Owen) scramble of Burley, "Practical
//    Hash-based Owen Scrambling", JCGT 9(4), 2020, seeded from (seed, group, dimension). Every group is an
//    independent randomisation of the same sequence, so group-to-group spread gives honest error bars.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::uncertainty {

enum class SamplingMethod { MonteCarlo, Sobol };

inline constexpr EnumTable<SamplingMethod, 2> kSamplingMethodNames{{
    {SamplingMethod::MonteCarlo, "monte-carlo", "pseudo-random points; error ~ 1/sqrt(N)"},
    {SamplingMethod::Sobol, "sobol",
     "Owen-scrambled Sobol' points (randomised quasi-Monte Carlo); error down to ~1/N for smooth outputs, use N = 2^m"},
}};
std::string_view to_string(SamplingMethod method);
// Throws InvalidInput naming `what` and listing the names for an unknown name.
SamplingMethod sampling_method_from_string(std::string_view name, std::string_view what);

// Rows per block (points are generated block by block).
inline constexpr std::size_t kSampleBlockRows = 1024;

// Rows [block·kSampleBlockRows, block·kSampleBlockRows + rows) of group `group`, row-major into `out`
// (rows·dimension values, each in (0, 1)). rows <= kSampleBlockRows; dimension in [1, 1000].
void uniform_points(SamplingMethod method, std::uint64_t seed, std::uint64_t group, std::size_t dimension,
                    std::size_t block, std::size_t rows, double* out);

// SplitMix64's finaliser: a well-mixed 64-bit hash of x.
std::uint64_t mix64(std::uint64_t x);

}  // namespace needlekit::uncertainty
