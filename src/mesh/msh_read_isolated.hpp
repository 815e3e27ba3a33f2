// Private to src/mesh: reading a .msh file with the Gmsh module in a child process.
//
// Gmsh 4.8's .msh readers (Debian bookworm's libgmsh) crash with SIGSEGV on some malformed files, for example an
// MSH 2.2 file whose $Nodes count is smaller than the nodes it lists and whose element uses the node left out
// (found by fuzz_gmsh_msh: tests/data/fuzz-regressions/gmsh_msh/fuzz_gmsh_msh2_node_count_segv.msh). A crash there
// is in Gmsh, but it would take the whole tool down with no message. So the file is read in a fork()ed child that
// sends the contents back through a socket; a child killed by a signal means Gmsh could not read the file.
//
// The child can stay for the next file (keep_process): forking a large process costs more than Gmsh's read of a small
// file (fuzz_gmsh_msh spent 78 % of its time in the kernel's copy of the page tables at one fork per input). The
// child initialises and finalises Gmsh for every file, as an in-process read does; one that crashed is replaced.
#pragma once
#include <string>
#include <vector>

#include "gmsh_module.hpp"

namespace needlekit::mesh::detail {

struct ReaderProcessOptions {
  bool keep_process = false;  // the child stays for the next call
  double cpu_limit = 0;       // s of CPU time (user and system) the child may spend on one file; 0: no limit
};

// The module's read_msh(file, layers) run in a child process. Throws InvalidInput naming the file when the child dies
// by a signal (its CPU time limit included) or fails, std::runtime_error when no child can be started; reports the
// module's own errors in `error`.
MshContents read_msh_isolated(const std::string& file, const std::vector<TissueLayer>& layers, GmshError& error,
                              const ReaderProcessOptions& options);

}  // namespace needlekit::mesh::detail
