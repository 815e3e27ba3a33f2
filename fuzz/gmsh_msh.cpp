// Gmsh .msh import (`[mesh] file`): Gmsh reads a file, so the bytes go to a temporary one first. The child process
// that runs Gmsh's reader is kept from one input to the next (it is replaced after any input it could not read).
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "fuzz_target.hpp"
#include "needlekit/mesh/msh_import.hpp"

NEEDLEKIT_FUZZ_TARGET(gmsh_msh) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("needlekit-fuzz-" + std::to_string(::getpid()) + ".msh");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  needlekit::fuzz::refusals_allowed([&] { needlekit::mesh::msh_import(file, {.unit = 1e-6, .keep_reader_process = true}); });
  std::error_code ignored;
  std::filesystem::remove(file, ignored);
}
