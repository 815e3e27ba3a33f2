// Internal: the PETSc backend's entry points for the rest of the library, without a PETSc or MPI header (those stay
// in this folder's .cpp files and petsc_linear_solve.hpp).
#pragma once
#include <memory>

#include "../linear_solve.hpp"

namespace needlekit::fem::detail {

// PETSc's CG + GAMG on `matrix` (laid out by tangent_layout(..., Petsc): with the nodal average, the patch term in
// the product and the one-ring P) across the processes of MPI_COMM_WORLD; starts MPI and PETSc if the process has
// not (parallel_session.hpp). Every rank must call it, with the same mesh.
std::unique_ptr<LinearSolve> make_petsc_linear_solve(TangentMatrix& matrix, const TangentInputs& inputs,
                                                     const SolverOptions& options);

// Starts MPI and PETSc once per process (parallel_session.cpp).
void start_petsc();

}  // namespace needlekit::fem::detail
