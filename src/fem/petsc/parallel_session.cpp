// parallel_session.hpp in a build with PETSc: MPI and PETSc started once per process, eagerly under mpirun and
// lazily otherwise, finalized by the session's destructor.
#include "needlekit/fem/parallel_session.hpp"

#include <petscsys.h>

#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "petsc_backend.hpp"

namespace needlekit::fem {
namespace {

struct SessionState {
  std::vector<std::string> arguments{"needlekit"};  // argv[0] and PETSc's options, for PetscInitialize
  bool started = false;
};
SessionState& state() {
  static SessionState s;
  return s;
}

// Options PETSc users pass on the command line: they go to PETSc, not to the program's own parser.
bool petsc_option(std::string_view a) {
  for (std::string_view prefix : {"-ksp_", "-pc_", "-mg_", "-log_view", "-options_file", "-help_petsc"})
    if (a.starts_with(prefix)) return true;
  return false;
}

// Open MPI's mpirun and PMI launchers (MPICH, Slurm) set these in every rank's environment.
bool launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}

}  // namespace

namespace detail {
void start_petsc() {
  SessionState& s = state();
  if (s.started) return;
  std::vector<char*> pointers;
  for (std::string& a : s.arguments) pointers.push_back(a.data());
  // needlekit keeps its own SIGINT/SIGTERM handling (exit 130 with complete files): PETSc installs none.
  static std::string no_signal_handler = "-no_signal_handler";
  pointers.push_back(no_signal_handler.data());
  pointers.push_back(nullptr);
  int argc = static_cast<int>(pointers.size()) - 1;
  char** argv = pointers.data();
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) std::abort();  // no MPI: nothing can run
  s.started = true;
}
}  // namespace detail

bool backend_compiled(SolverBackend) { return true; }
std::string compiled_backend_names() { return "builtin, petsc"; }

int process_rank() {
  if (!state().started) return 0;
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

int process_count() {
  if (!state().started) return 1;
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

ParallelSession::ParallelSession(int& argc, char** argv) {
  SessionState& s = state();
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (!petsc_option(argv[i])) {
      argv[kept++] = argv[i];
      continue;
    }
    s.arguments.emplace_back(argv[i]);
    if (i + 1 < argc && argv[i + 1][0] != '-') s.arguments.emplace_back(argv[++i]);  // the option's value
  }
  argc = kept;
  argv[argc] = nullptr;
  if (launched_by_mpirun()) detail::start_petsc();
}

ParallelSession::~ParallelSession() {
  if (state().started) PetscFinalize();
  state().started = false;
}

}  // namespace needlekit::fem
