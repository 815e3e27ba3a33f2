// Internal: LinearSolver::TwoGrid, a strategy of linear_solve.hpp: CG preconditioned by the two-grid cycle
// (two_grid_preconditioner.hpp) on K itself, or, with the nodal-averaged tetrahedron, by the Woodbury form of
// nodal_volume_preconditioner.hpp whose cycle runs on the stored one-ring element part (the tangent laid out with
// TangentLayout::patch_term_in_product). Memory and time per iteration linear in the mesh size.
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <memory>
#include <string>

#include "conjugate_gradients.hpp"
#include "linear_solve.hpp"
#include "nodal_volume_preconditioner.hpp"
#include "two_grid_preconditioner.hpp"

namespace needlekit::fem::detail {

class TwoGridSolve final : public LinearSolve {
public:
  // inputs.coarse: the coarse level (required); inputs.nodal: the nodal average whose patch term the product adds.
  TwoGridSolve(TangentMatrix& matrix, const TangentInputs& inputs, const SolverOptions& options,
               tbb::task_arena& arena);
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double forcing) override;
  std::string failure_reason() const override {
    return "the tangent system could not be solved (two-grid CG failed, also with a diagonal shift)";
  }
  double factor_nonzeros() const override;
  double factor_flops() const override;

private:
  template <class Prepare, class Preconditioner>
  bool cycle_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing,
                   Prepare&& prepare, Preconditioner&& precondition);

  TangentMatrix& matrix_;
  const SolverOptions& options_;
  ConjugateGradients cg_;
  std::unique_ptr<TwoGridPreconditioner> two_grid_;            // without a nodal average
  std::unique_ptr<NodalVolumePreconditioner> nodal_two_grid_;  // with one
  bool have_factor_ = false;    // the coarse operator is factorized
  int last_cg_iterations_ = 0;  // of the last CG solve
};

}  // namespace needlekit::fem::detail
