#include "needlekit/uncertainty/sample_points.hpp"

#include <boost/random/sobol.hpp>
#include <fmt/format.h>
#include <random>

#include "needlekit/core/errors.hpp"

namespace needlekit::uncertainty {
namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Burley 2020, Listing 3 (improved Laine–Karras hash): a random permutation of the bit-reversed value in which
// every bit depends only on the bits below it, i.e. on the higher-order digits of the original value.
std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Burley 2020, Listing 2: nested uniform scramble of a 32-bit binary fraction.
std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t group, std::uint64_t index) {
  return mix64(mix64(mix64(seed) ^ group) ^ index);
}

void monte_carlo_points(std::uint64_t seed, std::uint64_t group, std::size_t dimension, std::size_t block,
                        std::size_t rows, double* out) {
  std::mt19937_64 engine(stream_seed(seed, group, block));
  for (std::size_t i = 0; i < rows * dimension; ++i) {
    out[i] = (static_cast<double>(engine() >> 11) + 0.5) * 0x1p-53;
  }
}

void sobol_points(std::uint64_t seed, std::uint64_t group, std::size_t dimension, std::size_t block,
                  std::size_t rows, double* out) {
  boost::random::sobol_engine<std::uint32_t, 32> engine(dimension);
  std::vector<std::uint32_t> scramble(dimension);
  for (std::size_t j = 0; j < dimension; ++j) {
    scramble[j] = static_cast<std::uint32_t>(stream_seed(seed, group, 0x5eed0000u + j) >> 32);
  }
  std::size_t row = block * kSampleBlockRows;
  // Boost's sequence skips the origin: its n-th vector is Sobol' point n + 1; row 0 is the origin.
  if (row > 0) engine.seed(static_cast<std::uint32_t>(row - 1));
  for (std::size_t i = 0; i < rows; ++i, ++row) {
    for (std::size_t j = 0; j < dimension; ++j) {
      const std::uint32_t raw = row == 0 ? 0u : engine();
      out[i * dimension + j] = (static_cast<double>(nested_uniform_scramble(raw, scramble[j])) + 0.5) * 0x1p-32;
    }
  }
}

}  // namespace

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::string_view to_string(SamplingMethod method) { return name_of(kSamplingMethodNames, method); }

SamplingMethod sampling_method_from_string(std::string_view name, std::string_view what) {
  return value_of(kSamplingMethodNames, name, what);
}

void uniform_points(SamplingMethod method, std::uint64_t seed, std::uint64_t group, std::size_t dimension,
                    std::size_t block, std::size_t rows, double* out) {
  if (dimension < 1 || dimension > 1000 || rows > kSampleBlockRows) {
    throw InvalidInput(fmt::format("uniform_points: dimension {} (expected 1 to 1000) or rows {} (expected <= {})",
                                   dimension, rows, kSampleBlockRows));
  }
  if (method == SamplingMethod::MonteCarlo) {
    monte_carlo_points(seed, group, dimension, block, rows, out);
  } else {
    sobol_points(seed, group, dimension, block, rows, out);
  }
}

}  // namespace needlekit::uncertainty
