// Internal to run_indentation: one rezoning of the tissue between load steps (fem::SolverOptions::rezone). The
// deformed tissue is meshed anew (mesh/rezoned_mesh.hpp), a solver is built on the new mesh, and it is brought into
// equilibrium at the needles' current displacement, starting from the transferred displacement (Newton at a fixed
// needle position: the remap's residual is rebalanced before the run goes on).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::insertion::detail {

struct Rezoning {
  std::unique_ptr<fem::QuasiStaticSolver> solver;  // null: the rezoning failed, `failure` says why
  mesh::TetMesh tissue;                            // the new reference mesh
  Remesh record;                                   // step, depth, reason and failure are the caller's
  std::string failure;
};

// `tissue`: the reference mesh `solver` was built on; the solver's last converged state is rezoned. `step_force` and
// `step_volume_ratio`: that state's total force (N) and smallest J. Never throws for a numerical failure.
Rezoning rezoned(const mesh::TetMesh& tissue, const fem::QuasiStaticSolver& solver,
                 std::vector<fem::Indenter> indenters, const fem::SolverOptions& options, double step_force,
                 double step_volume_ratio);

}  // namespace needlekit::insertion::detail
