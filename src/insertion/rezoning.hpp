// Internal to run_indentation: rezoning the tissue between load steps (fem::SolverOptions::rezone). The
// deformed tissue is meshed anew (mesh/rezoned_mesh.hpp), a solver is built on the new mesh, and it is brought into
// equilibrium at the needles' current displacement, starting from the transferred displacement (Newton at a fixed
// needle position: the remap's residual is rebalanced before the run goes on).
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::insertion::detail {

struct Rezoning {
  std::unique_ptr<fem::QuasiStaticSolver> solver;  // null: the rezoning failed, record.failure says why
  mesh::TetMesh tissue;                            // the new reference mesh
  Remesh record;                                   // step, depth and reason are the caller's
};

// `tissue`: the reference mesh `solver` was built on; the solver's last converged state is rezoned. `step_force` and
// `step_volume_ratio`: that state's total force (N, the whole case's) and smallest J. `force_factor`: the whole
// case's total force over the solved model's (ArrayModel::factor: 1, 2 or 4 with a symmetric array's reduced model),
// so that the force after is the whole case's too. Never throws for a numerical failure.
Rezoning rezoned(const mesh::TetMesh& tissue, const fem::QuasiStaticSolver& solver,
                 std::vector<fem::Indenter> indenters, const fem::SolverOptions& options, double step_force,
                 double step_volume_ratio, double force_factor);

// The tissue as run_indentation's solver uses it (SolverOptions::rezone): the mesh meshed for the run, or its latest
// rezoning. Each rezoning is recorded in IndentationResult::remeshes, and IndentationOptions::on_mesh is called with
// the new mesh.
class RezonableTissue {
public:
  // `m`: the model solved; the three are kept by reference. `force_factor`: the whole case's total force over the
  // solved model's (ArrayModel::factor).
  RezonableTissue(const IndentationCase& m, const fem::SolverOptions& options, const mesh::TetMesh& meshed,
                  double force_factor)
      : m_(m), options_(options), meshed_(meshed), force_factor_(force_factor) {}

  // After load step k failed with `why`, the solver's last converged state `depth` below the surface: rezones it,
  // if rezoning is on and has remeshes left. Returns whether the step can be tried again on a new mesh.
  bool rezoned_after_failure(fem::QuasiStaticSolver& solver, int k, double depth, const std::string& why,
                             const IndentationOptions& options, IndentationResult& result);

  // After converged load step k (not the last), the last of result.steps: rezones when its smallest J fell below
  // rezone_volume_ratio.
  void rezone_if_crushed(fem::QuasiStaticSolver& solver, int k, const IndentationOptions& options,
                         IndentationResult& result);

private:
  bool allowed(const IndentationResult& result) const;
  // Rezones the solver's last converged state (at load step `step`, `depth` below the surface, with the total
  // `force` and smallest J `min_volume_ratio`) and, if that works, replaces the solver. Returns whether it did.
  bool rezone(fem::QuasiStaticSolver& solver, int step, double depth, double force, double min_volume_ratio,
              std::string reason, const IndentationOptions& options, IndentationResult& result);
  const mesh::TetMesh& current() const { return rezoned_ ? *rezoned_ : meshed_; }

  const IndentationCase& m_;
  const fem::SolverOptions& options_;
  const mesh::TetMesh& meshed_;
  double force_factor_;
  std::optional<mesh::TetMesh> rezoned_;
};

}  // namespace needlekit::insertion::detail
