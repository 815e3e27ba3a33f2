#include "needlekit/io/mesh_attribution.hpp"

#include <fmt/format.h>
#include <fnmatch.h>

#include <fstream>

namespace needlekit::io {
namespace {

bool starts_with(const std::string& text, std::string_view prefix) { return text.rfind(prefix, 0) == 0; }

// Whether the bullet's names (`...` before its first ':') include `file`.
bool names_file(const std::string& bullet, const std::string& file) {
  const std::string head = bullet.substr(0, bullet.find(": "));
  for (std::size_t open = head.find('`'); open != std::string::npos; open = head.find('`', open + 1)) {
    const std::size_t close = head.find('`', open + 1);
    if (close == std::string::npos) break;
    const std::string pattern = head.substr(open + 1, close - open - 1);
    if (::fnmatch(pattern.c_str(), file.c_str(), 0) == 0) return true;
    open = close;
  }
  return false;
}

}  // namespace

std::optional<MeshAttribution> mesh_attribution(const std::filesystem::path& mesh) {
  MeshAttribution result;
  result.readme = mesh.parent_path() / "README.md";
  std::ifstream in(result.readme);
  if (!in) return std::nullopt;
  std::vector<std::string> bullets;
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (starts_with(line, "## ")) {
      std::string title = line;
      for (char& c : title) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      inside = title.find("attribution") != std::string::npos;
      continue;
    }
    if (!inside || line.empty()) continue;
    if (starts_with(line, "- ")) {
      bullets.push_back(line.substr(2));
    } else if (starts_with(line, "  ") && !bullets.empty() && result.notices.empty()) {
      bullets.back().append(1, ' ').append(line, line.find_first_not_of(' '));
    } else {
      result.notices.push_back(line);
    }
  }
  const std::string file = mesh.filename().string();
  for (std::size_t i = 0; i < bullets.size(); ++i) {
    if (!names_file(bullets[i], file)) continue;
    if (i > 0 && bullets[i].find("the same attribution") != std::string::npos) result.entries.push_back(bullets[i - 1]);
    result.entries.push_back(bullets[i]);
  }
  if (result.entries.empty()) return std::nullopt;
  return result;
}

std::string missing_attribution_warning(const std::filesystem::path& mesh) {
  return fmt::format("no licence or attribution found for {} (no README.md beside it with an attribution section "
                     "naming the file): check the mesh's terms before sharing results made from it",
                     mesh.string());
}

}  // namespace needlekit::io
