#include "needlekit/materials/preset_key.hpp"

#include <cctype>

namespace needlekit::materials {

std::string preset_key(std::string_view name) {
  std::string out;
  for (char c : name) {
    if (c == ' ' || c == '_' || c == '-') continue;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

}  // namespace needlekit::materials
