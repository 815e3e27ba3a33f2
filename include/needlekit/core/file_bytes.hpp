// Reading a whole input file into memory, with the checks every reader needs: a directory, a device or a missing
// file is an IoError naming the path (a directory opened with std::ifstream reads as empty on Linux).
#pragma once
#include <filesystem>
#include <string>
#include <string_view>

namespace needlekit {

// The file's bytes. `what` names the kind of file in messages ("STL file", "force curve"). Throws IoError.
std::string read_file_bytes(const std::filesystem::path& path, std::string_view what);

}  // namespace needlekit
