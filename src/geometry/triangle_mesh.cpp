#include "needlekit/geometry/triangle_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>

#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/file_bytes.hpp"

namespace needlekit::geometry {
namespace {

// A triangle whose area is below this fraction of the squared bounding-box diagonal counts as degenerate: far
// below any real feature (a 1e-6 relative edge length gives 1e-12) and far above the rounding of a flat triangle.
constexpr double kDegenerateRelativeArea = 1e-14;

void check_indices(const TriangleMesh& mesh) {
  const auto n = static_cast<long long>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int index : mesh.triangles[t]) {
      if (index < 0 || index >= n) {
        throw InvalidInput(fmt::format("triangle mesh: triangle {} refers to vertex {}, expected an index in [0, {})",
                                       t, index, n));
      }
    }
  }
}

Eigen::AlignedBox3d bounding_box(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v);
  return box;
}

Eigen::Vector3d area_vector(const TriangleMesh& mesh, const std::array<int, 3>& t) {
  const Eigen::Vector3d& a = mesh.vertices[t[0]];
  return 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
}

void check_scale(double scale, std::string_view what) {
  if (!std::isfinite(scale) || scale <= 0) {
    throw InvalidInput(fmt::format("{}: scale {} must be a positive finite factor", what, scale));
  }
}

// ---- binary STL: 80-byte header, uint32 count, then per triangle 12 little-endian floats and a uint16 ----------
constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kTriangleBytes = 50;

void append_u32(std::string& out, std::uint32_t value) {
  for (int byte = 0; byte < 4; ++byte) out.push_back(static_cast<char>((value >> (8 * byte)) & 0xffu));
}
void append_float(std::string& out, double value) {
  append_u32(out, std::bit_cast<std::uint32_t>(static_cast<float>(value)));
}

std::uint32_t read_u32(std::string_view bytes, std::size_t offset) {
  std::uint32_t value = 0;
  for (int byte = 0; byte < 4; ++byte) {
    value |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[offset + byte])) << (8 * byte);
  }
  return value;
}
double read_float(std::string_view bytes, std::size_t offset) {
  return static_cast<double>(std::bit_cast<float>(read_u32(bytes, offset)));
}

// Builds a mesh from triangle corners, merging corners with identical coordinates into one vertex.
class VertexMerger {
public:
  int index_of(const Eigen::Vector3d& p) {
    // +0.0 turns −0.0 into +0.0 so that the two zeros share a key.
    const Key key{std::bit_cast<std::uint64_t>(p.x() + 0.0), std::bit_cast<std::uint64_t>(p.y() + 0.0),
                  std::bit_cast<std::uint64_t>(p.z() + 0.0)};
    const auto [it, inserted] = index_.try_emplace(key, static_cast<int>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(p);
    return it->second;
  }
  void add_triangle(const std::array<Eigen::Vector3d, 3>& corners) {
    mesh_.triangles.push_back({index_of(corners[0]), index_of(corners[1]), index_of(corners[2])});
  }
  TriangleMesh take() { return std::move(mesh_); }

private:
  using Key = std::array<std::uint64_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::size_t h = 0;
      for (std::uint64_t word : k) h ^= std::hash<std::uint64_t>{}(word) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
      return h;
    }
  };
  TriangleMesh mesh_;
  std::unordered_map<Key, int, KeyHash> index_;
};

TriangleMesh parse_binary_stl(std::string_view bytes, std::uint32_t count, std::string_view path,
                              double scale) {
  VertexMerger merger;
  for (std::uint32_t t = 0; t < count; ++t) {
    const std::size_t record = kHeaderBytes + 4 + static_cast<std::size_t>(t) * kTriangleBytes;
    std::array<Eigen::Vector3d, 3> corners;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) {
        const double value = read_float(bytes, record + 12 + 12 * c + 4 * k);  // skip the 12-byte normal
        if (!std::isfinite(value)) {
          throw IoError(fmt::format("{}: triangle {} has a non-finite coordinate", path, t));
        }
        corners[c][k] = scale * value;
      }
    }
    merger.add_triangle(corners);
  }
  return merger.take();
}

// ---- ASCII STL: solid name / facet normal n n n / outer loop / vertex x y z (×3) / endloop / endfacet / endsolid --
struct Token {
  std::string_view text;
  int line = 0;
};

std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    const char ch = text[i];
    if (ch == '\n') ++line;
    if (std::isspace(static_cast<unsigned char>(ch))) {
      ++i;
      continue;
    }
    const std::size_t start = i;
    while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    tokens.push_back({text.substr(start, i - start), line});
  }
  return tokens;
}

class AsciiStlParser {
public:
  AsciiStlParser(std::string_view text, std::string_view path, double scale)
      : tokens_(tokenize(text)), path_(path), scale_(scale),
        last_line_(1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'))) {}

  TriangleMesh parse() {
    VertexMerger merger;
    begin_solid();
    while (true) {
      const Token& token = next("'facet' or 'endsolid'");
      if (token.text == "endsolid") {
        skip_rest_of_line(token.line);  // the optional solid name
        if (pos_ == tokens_.size()) break;
        begin_solid();  // several solids in one file
        continue;
      }
      if (token.text != "facet") fail(token, "'facet' or 'endsolid'");
      expect("normal");
      for (int k = 0; k < 3; ++k) number();  // the stored normal is ignored: orientation comes from the order
      expect("outer");
      expect("loop");
      std::array<Eigen::Vector3d, 3> corners;
      for (auto& corner : corners) {
        expect("vertex");
        for (int k = 0; k < 3; ++k) corner[k] = scale_ * number();
      }
      expect("endloop");
      expect("endfacet");
      merger.add_triangle(corners);
    }
    return merger.take();
  }

private:
  [[noreturn]] void fail(const Token& token, std::string_view expected) const {
    throw IoError(fmt::format("{}:{}: expected {} in ASCII STL, got '{}'", path_, token.line, expected, token.text));
  }
  const Token& next(std::string_view expected) {
    if (pos_ == tokens_.size()) {
      throw IoError(fmt::format("{}:{}: unexpected end of ASCII STL, expected {}", path_, last_line_, expected));
    }
    return tokens_[pos_++];
  }
  void expect(std::string_view keyword) {
    const Token& token = next(fmt::format("'{}'", keyword));
    if (token.text != keyword) fail(token, fmt::format("'{}'", keyword));
  }
  double number() {
    const Token& token = next("a number");
    std::string_view text = token.text;
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(value)) fail(token, "a finite number");
    return value;
  }
  void begin_solid() {
    const Token& token = next("'solid'");
    if (token.text != "solid") fail(token, "'solid'");
    skip_rest_of_line(token.line);  // the optional solid name
  }
  void skip_rest_of_line(int line) {
    while (pos_ < tokens_.size() && tokens_[pos_].line == line) ++pos_;
  }

  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  std::string path_;
  double scale_;
  int last_line_;
};

bool starts_with_solid(std::string_view bytes) {
  const auto first = std::find_if_not(bytes.begin(), bytes.end(), [](char ch) {
    return std::isspace(static_cast<unsigned char>(ch));
  });
  return bytes.substr(static_cast<std::size_t>(first - bytes.begin())).starts_with("solid");
}

}  // namespace

double signed_volume(const TriangleMesh& mesh) {
  check_indices(mesh);
  if (mesh.vertices.empty()) return 0.0;
  // Divergence theorem: V = Σ (a − o)·((b − o) × (c − o)) / 6 for any origin o; the box centre keeps the terms small
  // (no cancellation for a mesh far from the origin).
  const Eigen::Vector3d o = bounding_box(mesh).center();
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]] - o, b = mesh.vertices[t[1]] - o, c = mesh.vertices[t[2]] - o;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6;
}

double surface_area(const TriangleMesh& mesh) {
  check_indices(mesh);
  double area = 0;
  for (const auto& t : mesh.triangles) area += area_vector(mesh, t).norm();
  return area;
}

MeshTopologyReport topology_report(const TriangleMesh& mesh) {
  check_indices(mesh);
  // Uses of each undirected edge {i < j}: how often as i → j and how often as j → i.
  struct EdgeUses {
    int forward = 0;
    int backward = 0;
  };
  std::unordered_map<std::uint64_t, EdgeUses> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int i = t[k], j = t[(k + 1) % 3];
      const auto lo = static_cast<std::uint64_t>(std::min(i, j)), hi = static_cast<std::uint64_t>(std::max(i, j));
      EdgeUses& uses = edges[(lo << 32) | hi];
      (i < j ? uses.forward : uses.backward) += 1;
    }
  }

  MeshTopologyReport report;
  report.consistently_oriented = true;
  for (const auto& [key, uses] : edges) {
    const int count = uses.forward + uses.backward;
    if (count == 1) ++report.boundary_edges;
    if (count > 2) ++report.non_manifold_edges;
    // A shared edge must be used once in each direction; an edge of more than two triangles cannot be.
    if (count >= 2 && (uses.forward != 1 || uses.backward != 1)) report.consistently_oriented = false;
  }
  report.closed = !mesh.triangles.empty() && report.boundary_edges == 0 && report.non_manifold_edges == 0;

  report.degenerate_triangles = static_cast<int>(degenerate_triangles(mesh).size());
  return report;
}

std::vector<int> degenerate_triangles(const TriangleMesh& mesh) {
  check_indices(mesh);
  const double threshold = kDegenerateRelativeArea * bounding_box(mesh).sizes().squaredNorm();
  std::vector<int> degenerate;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
    if (repeated || area_vector(mesh, t).norm() <= threshold) degenerate.push_back(static_cast<int>(i));
  }
  return degenerate;
}

void write_stl(const TriangleMesh& mesh, const std::filesystem::path& path, double scale) {
  check_indices(mesh);
  check_scale(scale, fmt::format("write_stl({})", path.string()));
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInput(fmt::format("{}: {} triangles do not fit in a binary STL (at most 2^32 − 1)", path.string(),
                                   mesh.triangles.size()));
  }

  std::string bytes;
  bytes.reserve(kHeaderBytes + 4 + kTriangleBytes * mesh.triangles.size());
  std::string header = "needlekit binary STL";  // must not start with "solid" (that marks ASCII files)
  header.resize(kHeaderBytes, ' ');
  bytes += header;
  append_u32(bytes, static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d n = area_vector(mesh, t).normalized();  // zero for a degenerate triangle
    for (int k = 0; k < 3; ++k) append_float(bytes, n[k]);
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) append_float(bytes, scale * mesh.vertices[t[c]][k]);
    }
    bytes.append(2, '\0');  // attribute byte count
  }

  write_file_atomically(path, bytes);  // readers never see a partial file
}

TriangleMesh welded_mesh(const TriangleMesh& mesh) {
  check_indices(mesh);
  VertexMerger merger;
  for (const auto& t : mesh.triangles)
    merger.add_triangle({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  return merger.take();
}

TriangleMesh read_stl(const std::filesystem::path& path, double scale) {
  check_scale(scale, fmt::format("read_stl({})", path.string()));
  return parse_stl(read_file_bytes(path, "STL file"), path.string(), scale);
}

TriangleMesh parse_stl(std::string_view bytes, std::string_view path, double scale) {
  check_scale(scale, fmt::format("read_stl({})", path));
  // Binary exactly when the size matches the triangle count in the header (some binary headers start with "solid").
  if (bytes.size() >= kHeaderBytes + 4) {
    const std::uint32_t count = read_u32(bytes, kHeaderBytes);
    if (bytes.size() == kHeaderBytes + 4 + kTriangleBytes * static_cast<std::size_t>(count)) {
      return parse_binary_stl(bytes, count, path, scale);
    }
  }
  if (starts_with_solid(bytes)) return AsciiStlParser(bytes, path, scale).parse();
  if (bytes.size() >= kHeaderBytes + 4) {
    throw IoError(fmt::format("{}: not an STL file: {} bytes do not match the binary size 84 + 50·{} and the file "
                              "does not start with 'solid'",
                              path, bytes.size(), read_u32(bytes, kHeaderBytes)));
  }
  throw IoError(fmt::format("{}: not an STL file: {} bytes, shorter than a binary header and not starting with "
                            "'solid'",
                            path, bytes.size()));
}

}  // namespace needlekit::geometry
