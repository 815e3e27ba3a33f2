// PLY 1.0 (Turk 1994; http://paulbourke.net/dataformats/ply/) into a polygon soup.
//
// Why needlekit reads PLY itself: CGAL 5.5's reader (the Debian bookworm version) dereferences a null pointer for a
// vertex whose coordinates are integers or uchar (valid PLY), calls back() on its empty element list for a
// `property` line before any `element` (both SIGSEGV), and allocates whatever a header or list count says
// (std::bad_alloc on a corrupted count). Making it safe needs a validating pass over the whole file, which is a PLY
// reader of its own; this one is that pass, and it keeps only what a triangle mesh needs.
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <string>

#include "needlekit/core/errors.hpp"
#include "polygon_soup.hpp"

namespace needlekit::geometry::detail {
namespace {

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct ScalarName {
  Scalar type;
  std::string_view name, alias;
  int bytes;
  double min, max;  // the range of an integer type (ASCII values are checked against it)
};
constexpr double kHuge = std::numeric_limits<double>::max();
constexpr std::array<ScalarName, 8> kScalars{{{Scalar::Int8, "char", "int8", 1, -128, 127},
                                              {Scalar::UInt8, "uchar", "uint8", 1, 0, 255},
                                              {Scalar::Int16, "short", "int16", 2, -32768, 32767},
                                              {Scalar::UInt16, "ushort", "uint16", 2, 0, 65535},
                                              {Scalar::Int32, "int", "int32", 4, -2147483648.0, 2147483647.0},
                                              {Scalar::UInt32, "uint", "uint32", 4, 0, 4294967295.0},
                                              {Scalar::Float32, "float", "float32", 4, -kHuge, kHuge},
                                              {Scalar::Float64, "double", "float64", 8, -kHuge, kHuge}}};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

std::optional<ScalarName> scalar_named(std::string_view name) {
  for (const ScalarName& s : kScalars)
    if (name == s.name || name == s.alias) return s;
  return std::nullopt;
}

bool is_integer(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

struct Property {
  std::string name;
  ScalarName value;
  std::optional<ScalarName> list_count;  // set for a list property
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  int line = 0;
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;
};

std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

class HeaderParser {
public:
  HeaderParser(std::string_view bytes, std::string_view source) : bytes_(bytes), source_(source) {}

  Header parse() {
    Header header;
    bool have_format = false;
    while (true) {
      const std::optional<std::string_view> line = next_line();
      if (!line) fail("the header has no end_header line");
      const auto words = words_of(*line);
      if (line_ == 1) {
        if (words.size() != 1 || words[0] != "ply") fail("expected 'ply' as the first line");
        continue;
      }
      if (words.empty()) continue;
      const std::string_view keyword = words[0];
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "end_header") break;
      if (!have_format) {
        if (keyword != "format" || words.size() != 3) fail("expected 'format ascii|binary_little_endian|"
                                                           "binary_big_endian 1.0' as the second line");
        if (words[1] == "ascii") header.format = Format::Ascii;
        else if (words[1] == "binary_little_endian") header.format = Format::BinaryLittleEndian;
        else if (words[1] == "binary_big_endian") header.format = Format::BinaryBigEndian;
        else fail(fmt::format("unknown format '{}', expected ascii, binary_little_endian or binary_big_endian",
                              words[1]));
        if (words[2] != "1.0" && words[2] != "1") fail(fmt::format("version '{}', expected 1.0", words[2]));
        have_format = true;
        continue;
      }
      if (keyword == "element") {
        if (words.size() != 3) fail("expected 'element NAME COUNT'");
        Element element{std::string(words[1]), 0, {}, line_};
        const auto [end, ec] = std::from_chars(words[2].data(), words[2].data() + words[2].size(), element.count);
        if (ec != std::errc{} || end != words[2].data() + words[2].size())
          fail(fmt::format("element count '{}' is not a non-negative integer", words[2]));
        for (const Element& other : header.elements)
          if (other.name == element.name) fail(fmt::format("element '{}' is declared twice", element.name));
        header.elements.push_back(std::move(element));
        continue;
      }
      if (keyword == "property") {
        if (header.elements.empty()) fail("a property before any element; expected 'element NAME COUNT' first");
        Property property;
        if (words.size() == 5 && words[1] == "list") {
          property.list_count = scalar_named(words[2]);
          const auto value = scalar_named(words[3]);
          if (!property.list_count || !value) fail(fmt::format("unknown list types '{} {}'", words[2], words[3]));
          if (!is_integer(property.list_count->type)) fail(fmt::format("list count type '{}' is not an integer",
                                                                       words[2]));
          property.value = *value;
          property.name = words[4];
        } else if (words.size() == 3 && words[1] != "list") {
          const auto value = scalar_named(words[1]);
          if (!value) fail(fmt::format("unknown property type '{}', expected char, uchar, short, ushort, int, uint, "
                                       "float, double (or int8 ... float64)",
                                       words[1]));
          property.value = *value;
          property.name = words[2];
        } else {
          fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
        }
        for (const Property& other : header.elements.back().properties)
          if (other.name == property.name) fail(fmt::format("property '{}' is declared twice", property.name));
        header.elements.back().properties.push_back(std::move(property));
        continue;
      }
      fail(fmt::format("unknown header keyword '{}'", keyword));
    }
    if (!have_format) fail("no format line");
    header.body_offset = offset_;
    return header;
  }

private:
  std::optional<std::string_view> next_line() {
    if (offset_ >= bytes_.size()) return std::nullopt;
    const std::size_t end = bytes_.find('\n', offset_);
    const std::size_t stop = end == std::string_view::npos ? bytes_.size() : end;
    const std::string_view line = bytes_.substr(offset_, stop - offset_);
    offset_ = end == std::string_view::npos ? bytes_.size() : end + 1;
    ++line_;
    return line;
  }
  [[noreturn]] void fail(std::string_view what) const {
    throw IoError(fmt::format("{}:{}: PLY header: {}", source_, line_, what));
  }

  std::string_view bytes_;
  std::string_view source_;
  std::size_t offset_ = 0;
  int line_ = 0;
};

// Reads the values of the body one at a time, as doubles (every PLY scalar fits a double exactly).
class BodyReader {
public:
  BodyReader(std::string_view body, Format format, std::string_view source)
      : body_(body), format_(format), source_(source) {}

  double value(const ScalarName& type) {
    return format_ == Format::Ascii ? ascii_value(type) : binary_value(type);
  }
  // A list's length, checked against what is left of the body (each entry needs at least one byte).
  std::uint64_t list_length(const ScalarName& type, const Element& element, std::uint64_t item) {
    const double length = value(type);
    if (length < 0) fail(element, item, fmt::format("negative list length {}", length));
    const auto n = static_cast<std::uint64_t>(length);
    if (n > remaining()) fail(element, item, fmt::format("a list of {} entries is longer than the rest of the file", n));
    return n;
  }
  std::size_t remaining() const { return body_.size() - offset_; }
  [[noreturn]] void fail(const Element& element, std::uint64_t item, std::string_view what) const {
    throw IoError(fmt::format("{}: PLY {} {} (element declared on line {}): {}", source_, element.name, item,
                              element.line, what));
  }
  const Element* current = nullptr;
  std::uint64_t current_item = 0;

private:
  double ascii_value(const ScalarName& type) {
    while (offset_ < body_.size() && is_space(body_[offset_])) ++offset_;
    const std::size_t start = offset_;
    while (offset_ < body_.size() && !is_space(body_[offset_])) ++offset_;
    const std::string_view token = body_.substr(start, offset_ - start);
    if (token.empty()) fail(*current, current_item, "the file ends early");
    double v = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc{} || end != token.data() + token.size())
      fail(*current, current_item, fmt::format("'{}' is not a number", token));
    if (is_integer(type.type) && !(v == std::floor(v) && v >= type.min && v <= type.max))
      fail(*current, current_item, fmt::format("'{}' is not a {} (an integer in [{}, {}])", token, type.name,
                                               type.min, type.max));
    return v;
  }
  double binary_value(const ScalarName& type) {
    if (remaining() < static_cast<std::size_t>(type.bytes)) fail(*current, current_item, "the file ends early");
    std::uint64_t bits = 0;
    for (int b = 0; b < type.bytes; ++b) {
      const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(body_[offset_ + b]));
      const int shift = format_ == Format::BinaryLittleEndian ? 8 * b : 8 * (type.bytes - 1 - b);
      bits |= byte << shift;
    }
    offset_ += type.bytes;
    switch (type.type) {
      case Scalar::Int8: return static_cast<std::int8_t>(bits);
      case Scalar::UInt8: return static_cast<std::uint8_t>(bits);
      case Scalar::Int16: return static_cast<std::int16_t>(bits);
      case Scalar::UInt16: return static_cast<std::uint16_t>(bits);
      case Scalar::Int32: return static_cast<std::int32_t>(bits);
      case Scalar::UInt32: return static_cast<std::uint32_t>(bits);
      case Scalar::Float32: return std::bit_cast<float>(static_cast<std::uint32_t>(bits));
      case Scalar::Float64: return std::bit_cast<double>(bits);
    }
    return 0;
  }

  std::string_view body_;
  Format format_;
  std::string_view source_;
  std::size_t offset_ = 0;
};

// The fewest body bytes one item of the element can take: binary, its fixed-size scalars and list counts; ASCII,
// one character and one separator per value.
std::uint64_t min_item_bytes(const Element& element, Format format) {
  std::uint64_t bytes = 0;
  for (const Property& p : element.properties) {
    if (format == Format::Ascii) bytes += 2;
    else bytes += static_cast<std::uint64_t>(p.list_count ? p.list_count->bytes : p.value.bytes);
  }
  return bytes;
}

int property_index(const Element& element, std::initializer_list<std::string_view> names) {
  for (std::size_t i = 0; i < element.properties.size(); ++i)
    for (std::string_view name : names)
      if (element.properties[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace

PolygonSoup read_ply_soup(std::string_view bytes, std::string_view source_name) {
  const Header header = HeaderParser(bytes, source_name).parse();
  const std::string_view body = bytes.substr(header.body_offset);
  // Every count against the file's size, before anything is read or allocated. An ASCII file may end without a
  // separator after its last value, hence the + 1.
  std::uint64_t needed = 0;
  for (const Element& element : header.elements) {
    const std::uint64_t per_item = min_item_bytes(element, header.format);
    if (per_item == 0) {  // no properties: nothing to read (and nothing to loop over)
      if (element.count == 0) continue;
      throw IoError(fmt::format("{}:{}: PLY element '{}' has {} items but no properties; expected properties",
                                source_name, element.line, element.name, element.count));
    }
    if (element.count > (body.size() + 1) / per_item || needed + element.count * per_item > body.size() + 1) {
      throw IoError(fmt::format("{}:{}: PLY element '{}' declares {} items of at least {} bytes each, but the file "
                                "has {} bytes after its header ({} of them needed by the elements before it)",
                                source_name, element.line, element.name, element.count, per_item, body.size(),
                                needed));
    }
    needed += element.count * per_item;
  }

  PolygonSoup soup;
  BodyReader reader(body, header.format, source_name);
  bool have_vertices = false, have_faces = false;
  for (const Element& element : header.elements) {
    reader.current = &element;
    const bool vertices = element.name == "vertex" || element.name == "vertices";
    const bool faces = element.name == "face" || element.name == "faces";
    std::array<int, 3> xyz{-1, -1, -1};
    int indices = -1;
    if (vertices) {
      if (have_vertices) throw IoError(fmt::format("{}:{}: a second vertex element", source_name, element.line));
      have_vertices = true;
      xyz = {property_index(element, {"x"}), property_index(element, {"y"}), property_index(element, {"z"})};
      for (int k = 0; k < 3; ++k) {
        if (xyz[k] < 0 || element.properties[xyz[k]].list_count) {
          throw IoError(fmt::format("{}:{}: PLY vertex element has no scalar property '{}'", source_name,
                                    element.line, "xyz"[k]));
        }
      }
      soup.points.reserve(element.count);
    } else if (faces) {
      if (have_faces) throw IoError(fmt::format("{}:{}: a second face element", source_name, element.line));
      have_faces = true;
      indices = property_index(element, {"vertex_indices", "vertex_index"});
      if (indices < 0 || !element.properties[indices].list_count ||
          !is_integer(element.properties[indices].value.type)) {
        throw IoError(fmt::format("{}:{}: PLY face element has no integer list property vertex_indices (or "
                                  "vertex_index)",
                                  source_name, element.line));
      }
      soup.polygons.reserve(element.count);
    }
    for (std::uint64_t item = 0; item < element.count; ++item) {
      reader.current_item = item;
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      std::vector<std::int64_t> polygon;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.list_count) {
          const double v = reader.value(property.value);
          for (int k = 0; k < 3; ++k)
            if (xyz[k] == static_cast<int>(p)) point[k] = v;
          continue;
        }
        const std::uint64_t n = reader.list_length(*property.list_count, element, item);
        if (static_cast<int>(p) == indices) polygon.reserve(n);
        for (std::uint64_t i = 0; i < n; ++i) {
          const double v = reader.value(property.value);
          if (static_cast<int>(p) == indices) polygon.push_back(static_cast<std::int64_t>(v));
        }
      }
      if (vertices) soup.points.push_back(point);
      if (faces) soup.polygons.push_back(std::move(polygon));
    }
  }
  return soup;
}

}  // namespace needlekit::geometry::detail
