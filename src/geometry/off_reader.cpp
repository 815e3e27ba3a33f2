// ASCII OFF (Geomview's Object File Format) into a polygon soup, one vertex or face per line.
//
// Why needlekit reads OFF itself: CGAL 5.5's reader resizes its point, face and per-face index vectors to the counts
// the file declares before reading them, so a corrupted header or face line ends in std::bad_alloc (or exhausts
// memory); checking the counts first needs the header parsed, and the format is a few lines of text.
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <string>

#include "needlekit/core/errors.hpp"
#include "polygon_soup.hpp"

namespace needlekit::geometry::detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

class OffLines {
public:
  OffLines(std::string_view bytes, std::string_view source) : bytes_(bytes), source_(source) {}

  // The words of the next line that has any (comments after '#' removed); empty at the end of the file.
  std::vector<std::string_view> next() {
    while (offset_ < bytes_.size()) {
      const std::size_t end = bytes_.find('\n', offset_);
      const std::size_t stop = end == std::string_view::npos ? bytes_.size() : end;
      std::string_view line = bytes_.substr(offset_, stop - offset_);
      offset_ = end == std::string_view::npos ? bytes_.size() : end + 1;
      ++line_;
      if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
      std::vector<std::string_view> words;
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
      }
      if (!words.empty()) return words;
    }
    return {};
  }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  [[noreturn]] void fail(std::string_view what) const {
    throw IoError(fmt::format("{}:{}: OFF: {}", source_, line_, what));
  }
  template <class T>
  T number(std::string_view word, std::string_view what) const {
    T value{};
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc{} || end != word.data() + word.size()) fail(fmt::format("{} '{}' is not valid", what, word));
    return value;
  }

private:
  std::string_view bytes_;
  std::string_view source_;
  std::size_t offset_ = 0;
  int line_ = 0;
};

struct Keyword {
  bool homogeneous = false;  // 4OFF: x y z w
};

// [ST][C][N][4][n]OFF; nothing else.
std::optional<Keyword> keyword_of(std::string_view word) {
  if (!word.ends_with("OFF")) return std::nullopt;
  std::string_view prefix = word.substr(0, word.size() - 3);
  Keyword keyword;
  for (std::string_view part : {"ST", "C", "N", "4", "n"}) {
    if (!prefix.starts_with(part)) continue;
    if (part == "4") keyword.homogeneous = true;
    if (part == "n") return std::nullopt;  // nOFF (another dimension): refused below
    prefix.remove_prefix(part.size());
  }
  if (!prefix.empty()) return std::nullopt;
  return keyword;
}

}  // namespace

PolygonSoup read_off_soup(std::string_view bytes, std::string_view source_name) {
  OffLines lines(bytes, source_name);
  std::vector<std::string_view> words = lines.next();
  if (words.empty()) lines.fail("the file is empty, expected 'OFF' and the counts");
  const std::optional<Keyword> keyword = keyword_of(words[0]);
  if (!keyword) {
    lines.fail(fmt::format("expected the keyword OFF (or COFF, NOFF, STOFF, 4OFF), got '{}'{}", words[0],
                           words[0].ends_with("nOFF") ? " (nOFF is not supported)" : ""));
  }
  words.erase(words.begin());
  if (!words.empty() && words[0] == "BINARY") lines.fail("binary OFF is not supported; write it as ASCII OFF");
  if (words.empty()) words = lines.next();
  if (words.size() < 2 || words.size() > 3) lines.fail("expected the counts 'vertices faces [edges]'");
  const auto vertices = lines.number<std::uint64_t>(words[0], "vertex count");
  const auto faces = lines.number<std::uint64_t>(words[1], "face count");
  // A vertex line takes at least 6 bytes ("0 0 0\n"), a face line at least 2; the last line may lack its newline.
  const std::uint64_t room = lines.remaining() + 1;
  if (vertices > room / 6 || faces > room / 2 || 6 * vertices + 2 * faces > room) {
    lines.fail(fmt::format("the header declares {} vertices and {} faces, more than the {} bytes after it can hold",
                           vertices, faces, lines.remaining()));
  }

  PolygonSoup soup;
  soup.points.reserve(vertices);
  const std::size_t coordinates = keyword->homogeneous ? 4 : 3;
  for (std::uint64_t v = 0; v < vertices; ++v) {
    words = lines.next();
    if (words.size() < coordinates) {
      lines.fail(fmt::format("vertex {} of {}: {} numbers, expected at least {}", v, vertices, words.size(),
                             coordinates));
    }
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = lines.number<double>(words[k], "coordinate");
    if (keyword->homogeneous) p /= lines.number<double>(words[3], "homogeneous coordinate");
    soup.points.push_back(p);
  }
  soup.polygons.reserve(faces);
  for (std::uint64_t f = 0; f < faces; ++f) {
    words = lines.next();
    if (words.empty()) lines.fail(fmt::format("the file ends at face {} of {}", f, faces));
    const auto corners = lines.number<std::uint64_t>(words[0], "corner count");
    if (corners > words.size() - 1) {
      lines.fail(fmt::format("face {} declares {} corners but the line has {} indices", f, corners,
                             words.size() - 1));
    }
    std::vector<std::int64_t> polygon;
    polygon.reserve(corners);
    for (std::uint64_t c = 0; c < corners; ++c)
      polygon.push_back(lines.number<std::int64_t>(words[1 + c], "vertex index"));
    soup.polygons.push_back(std::move(polygon));
  }
  return soup;
}

}  // namespace needlekit::geometry::detail
