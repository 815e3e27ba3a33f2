#include "linear_solve.hpp"

#include "cholesky_solve.hpp"
#if NEEDLEKIT_WITH_PETSC
#include "petsc/petsc_backend.hpp"
#endif
#include "split_preconditioned_solve.hpp"
#include "two_grid_solve.hpp"

namespace needlekit::fem::detail {

const std::vector<char>& LinearSolve::assembled_elements() const {
  static const std::vector<char> every_element;
  return every_element;
}

TangentLayout tangent_layout(SolverBackend backend, LinearSolver solver, bool nodal_average) {
  TangentLayout layout;
  if (backend == SolverBackend::Petsc) {  // petsc_patch_operator.hpp: K = A + G D G^T as a shell, GAMG on P
    layout.patch_term_in_product = layout.one_ring_preconditioner = nodal_average;
    return layout;
  }
  layout.patch_term_in_product = nodal_average && solver == LinearSolver::TwoGrid;
  layout.one_ring_preconditioner = nodal_average && solver == LinearSolver::CholeskyCg;
  return layout;
}

std::unique_ptr<LinearSolve> make_linear_solve(LinearSolver solver, TangentMatrix& matrix, const TangentInputs& inputs,
                                               const SolverOptions& options, tbb::task_arena& arena) {
#if NEEDLEKIT_WITH_PETSC
  if (options.backend == SolverBackend::Petsc) return make_petsc_linear_solve(matrix, inputs, options);
#endif
  if (solver == LinearSolver::TwoGrid) return std::make_unique<TwoGridSolve>(matrix, inputs, options, arena);
  if (matrix.splits_preconditioner()) return std::make_unique<SplitPreconditionedSolve>(matrix, options);
  return std::make_unique<CholeskySolve>(matrix, options, solver == LinearSolver::CholeskyCg);
}

}  // namespace needlekit::fem::detail
