// How preset names compare: case-insensitive, with ' ', '_' and '-' ignored ("SU-8" == "su8", "Silicone_0.2MPa" ==
// "silicone-0.2mpa").
#pragma once
#include <string>
#include <string_view>

namespace needlekit::materials {

// The lower-case name without ' ', '_' and '-'.
std::string preset_key(std::string_view name);

}  // namespace needlekit::materials
