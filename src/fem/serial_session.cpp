// parallel_session.hpp in a build without PETSc: the built-in backend alone, one process.
#include "needlekit/fem/parallel_session.hpp"

namespace needlekit::fem {

bool backend_compiled(SolverBackend backend) { return backend == SolverBackend::Builtin; }
std::string compiled_backend_names() { return "builtin"; }
int process_rank() { return 0; }
int process_count() { return 1; }
ParallelSession::ParallelSession(int&, char**) {}
ParallelSession::~ParallelSession() = default;

}  // namespace needlekit::fem
