#include "needlekit/io/view_arrays.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "needlekit/core/errors.hpp"

namespace needlekit::io {
namespace {

static_assert(std::endian::native == std::endian::little, "the view arrays are written in the machine's byte order");

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int sextet(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

template <typename T>
nlohmann::json typed_array(const char* dtype, std::span<const T> values) {
  std::vector<std::uint8_t> bytes(values.size_bytes());
  if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return {{"dtype", dtype}, {"count", values.size()}, {"base64", base64_encode(bytes)}};
}

template <typename T>
std::vector<T> values_of(const std::vector<std::uint8_t>& bytes, std::size_t count, const std::string& dtype) {
  if (bytes.size() != count * sizeof(T)) {
    throw InvalidInput(fmt::format("view array: {} {} values need {} bytes, the base64 holds {}", count, dtype,
                                   count * sizeof(T), bytes.size()));
  }
  std::vector<T> values(count);
  if (count > 0) std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

}  // namespace

std::string base64_encode(std::span<const std::uint8_t> bytes) {
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    for (int shift : {18, 12, 6, 0}) text += kAlphabet[(v >> shift) & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    const std::uint32_t v = (bytes[i] << 16) | (rest == 2 ? bytes[i + 1] << 8 : 0);
    text += kAlphabet[(v >> 18) & 63];
    text += kAlphabet[(v >> 12) & 63];
    text += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    text += '=';
  }
  return text;
}

std::vector<std::uint8_t> base64_decode(std::string_view text) {
  if (text.size() % 4 != 0) {
    throw InvalidInput(fmt::format("base64: the length {} is not a multiple of 4", text.size()));
  }
  std::vector<std::uint8_t> bytes;
  bytes.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) {
      const int s = k >= 4 - pad ? 0 : sextet(text[i + k]);
      if (s < 0) throw InvalidInput(fmt::format("base64: character {} ('{}') is not base64", i + k, text[i + k]));
      v = (v << 6) | static_cast<std::uint32_t>(s);
    }
    bytes.push_back(static_cast<std::uint8_t>(v >> 16));
    if (pad < 2) bytes.push_back(static_cast<std::uint8_t>((v >> 8) & 255));
    if (pad < 1) bytes.push_back(static_cast<std::uint8_t>(v & 255));
  }
  return bytes;
}

nlohmann::json float32_array(std::span<const float> values) { return typed_array("float32", values); }

nlohmann::json uint32_array(std::span<const std::uint32_t> values) { return typed_array("uint32", values); }

nlohmann::json quantized_array(std::span<const float> values, int components) {
  if (components < 1 || values.size() % components != 0) {
    throw InvalidInput(fmt::format("quantized view array: {} values are not items of {} components", values.size(),
                                   components));
  }
  std::vector<float> lo(components, std::numeric_limits<float>::max());
  std::vector<float> hi(components, std::numeric_limits<float>::lowest());
  for (std::size_t k = 0; k < values.size(); ++k) {
    lo[k % components] = std::min(lo[k % components], values[k]);
    hi[k % components] = std::max(hi[k % components], values[k]);
  }
  if (values.empty()) std::fill(lo.begin(), lo.end(), 0.0f), std::fill(hi.begin(), hi.end(), 0.0f);
  std::vector<std::uint16_t> codes(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const int c = static_cast<int>(k % components);
    const double range = static_cast<double>(hi[c]) - lo[c];
    codes[k] = range > 0 ? static_cast<std::uint16_t>(std::lround((values[k] - lo[c]) / range * 65535.0)) : 0;
  }
  nlohmann::json array = typed_array<std::uint16_t>("uint16", codes);
  array["components"] = components;
  array["lo"] = lo;
  array["hi"] = hi;
  return array;
}

std::vector<double> decoded_array(const nlohmann::json& array) {
  const std::string dtype = array.at("dtype").get<std::string>();
  const std::size_t count = array.at("count").get<std::size_t>();
  const std::vector<std::uint8_t> bytes = base64_decode(array.at("base64").get<std::string>());
  if (dtype == "float32") {
    const std::vector<float> v = values_of<float>(bytes, count, dtype);
    return {v.begin(), v.end()};
  }
  if (dtype == "uint32") {
    const std::vector<std::uint32_t> v = values_of<std::uint32_t>(bytes, count, dtype);
    return {v.begin(), v.end()};
  }
  if (dtype == "uint16") {
    const std::vector<std::uint16_t> v = values_of<std::uint16_t>(bytes, count, dtype);
    if (!array.contains("lo")) return {v.begin(), v.end()};
    const std::vector<double> lo = array.at("lo").get<std::vector<double>>();
    const std::vector<double> hi = array.at("hi").get<std::vector<double>>();
    std::vector<double> values(count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t c = k % lo.size();
      values[k] = lo[c] + v[k] * (hi[c] - lo[c]) / 65535.0;
    }
    return values;
  }
  throw InvalidInput(fmt::format("view array: unknown dtype '{}', expected float32, uint32 or uint16", dtype));
}

}  // namespace needlekit::io
