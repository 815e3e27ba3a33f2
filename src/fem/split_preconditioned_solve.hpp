// Internal: LinearSolver::CholeskyCg with the nodal-averaged tetrahedron (nodal_volume.hpp), a strategy of
// linear_solve.hpp. The node patches make K's pattern the mesh's two-ring, whose Cholesky factor costs several times
// the one-ring's (measured 8x the CPU of a Newton solve on the §6.2 phantom). CG therefore runs on the full K,
// preconditioned by the factor of a one-ring matrix P that the assembly provides (TangentMatrix::
// capture_preconditioner + preconditioner_values: the element part of K plus a per-element bulk term that bounds the
// nodal one from above). K itself is never factorized.
#pragma once
#include <Eigen/Core>

#include "cholesky_solve.hpp"

namespace needlekit::fem::detail {

class SplitPreconditionedSolve final : public FactorSolve {
public:
  // `matrix` laid out with a one-ring preconditioner (TangentLayout::one_ring_preconditioner).
  SplitPreconditionedSolve(TangentMatrix& matrix, const SolverOptions& options)
      : FactorSolve(matrix, options, matrix.preconditioner_pattern()) {}
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double forcing) override;

private:
  int fresh_cg_iterations_ = 0;  // of the last solve on a fresh factor of P
};

}  // namespace needlekit::fem::detail
