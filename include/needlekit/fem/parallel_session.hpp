// The backends of the FE solver's linear solves compiled into this build, and the process's MPI/PETSc session for
// the PETSc backend (docs/fem_solver.md, "PETSc backend"). No PETSc or MPI header here: they stay in src/fem/petsc/.
#pragma once
#include <string>

#include "needlekit/fem/solver_options.hpp"

namespace needlekit::fem {

// Whether this build has `backend` (Builtin always; Petsc with NEEDLEKIT_WITH_PETSC).
bool backend_compiled(SolverBackend backend);
// The names of the compiled backends, comma-separated ("builtin, petsc"): for --version and error messages.
std::string compiled_backend_names();

// This process's rank among the MPI processes and their number: 0 and 1 without MPI (or before it started).
int process_rank();
int process_count();

// MPI and PETSc for this process, once. Create one at the top of main(), before anything else runs: under mpirun
// (Open MPI's or a PMI launcher's environment) it starts MPI at once, so that every rank knows its rank; otherwise
// the first PETSc solve starts it (a single process). Its destructor finalizes PETSc and MPI if they were started.
// The constructor takes PETSc's own options (-ksp_*, -pc_*, -mg_*, -log_view, -options_file: what PETSc users pass)
// out of argv, for the solver's KSPSetFromOptions; PETSC_OPTIONS in the environment works too. In a build without
// PETSc it does nothing.
class ParallelSession {
public:
  ParallelSession(int& argc, char** argv);
  ~ParallelSession();
  ParallelSession(const ParallelSession&) = delete;
  ParallelSession& operator=(const ParallelSession&) = delete;
};

}  // namespace needlekit::fem
