// Typed arrays for the report's 3D views (docs/views.md): little-endian Float32 / Uint32 / Uint16 arrays encoded as
// base64 (RFC 4648, with padding) inside JSON objects that the viewer decodes into JavaScript typed arrays
// (Float32Array, Uint32Array, Uint16Array) without parsing numbers.
//
// An array is {"dtype": "float32" | "uint32" | "uint16", "count": N, "base64": "..."}. A quantized array also has
// "components": C, "lo": [C numbers], "hi": [C numbers]: value k of component c is lo[c] + q_k (hi[c] − lo[c]) / 65535
// (q_k the Uint16), i.e. at most (hi − lo) / 131070 from the value written.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace needlekit::io {

std::string base64_encode(std::span<const std::uint8_t> bytes);
// Throws InvalidInput for a length that is not a multiple of 4 or a character outside the base64 alphabet.
std::vector<std::uint8_t> base64_decode(std::string_view text);

nlohmann::json float32_array(std::span<const float> values);
nlohmann::json uint32_array(std::span<const std::uint32_t> values);
// `values` holds `components` interleaved components per item (e.g. x, y, z); lo and hi are per component over all
// items (equal lo and hi give all-zero codes).
nlohmann::json quantized_array(std::span<const float> values, int components);

// The values of any of the arrays above (quantized ones de-quantized), for tests and tools. Throws InvalidInput for
// an unknown dtype or a count that does not match the bytes.
std::vector<double> decoded_array(const nlohmann::json& array);

}  // namespace needlekit::io
