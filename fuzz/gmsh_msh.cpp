// Gmsh .msh import (`[mesh] file`): Gmsh reads a file, so the bytes go to a temporary one first. The child process
// that runs Gmsh's reader is kept from one input to the next (it is replaced after any input it could not read), and
// it may spend 0.05 s of CPU time on one input (a well-formed input of 8 KB reads in about 5 ms here): about 5 % of
// mutated inputs make Gmsh's reader loop over a count read from garbage, growing to 0.5-1 GB in 2-3 s before an
// allocation hits the malloc limit, which held the target to 20-40 executions/s (docs/reliability.md).
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
  needlekit::fuzz::refusals_allowed([&] { needlekit::mesh::msh_import(file, {.unit = 1e-6, .keep_reader_process = true, .reader_cpu_limit = 0.05}); });
  std::error_code ignored;
  std::filesystem::remove(file, ignored);
}
