#include "rezoning.hpp"

#include <chrono>
#include <exception>
#include <numeric>

#include "needlekit/mesh/rezoned_mesh.hpp"

namespace needlekit::insertion::detail {

Rezoning rezoned(const mesh::TetMesh& tissue, const fem::QuasiStaticSolver& solver,
                 std::vector<fem::Indenter> indenters, const fem::SolverOptions& options, double step_force,
                 double step_volume_ratio) {
  const auto start = std::chrono::steady_clock::now();
  Rezoning out;
  out.record.elements_before = static_cast<int>(tissue.tets.size());
  out.record.force_before = step_force;
  out.record.min_volume_ratio_before = step_volume_ratio;
  try {
    mesh::RezoneOptions rezone;
    rezone.volume_ratio = options.rezone_volume_ratio;  // only the crushed neighbourhoods (a failed step: all if none)
    mesh::RezonedMesh rezoned = mesh::rezoned_mesh(tissue, solver.displacement(), rezone);
    auto next = std::make_unique<fem::QuasiStaticSolver>(rezoned.mesh, std::move(indenters), options);
    const fem::StepResult balanced = next->advance_to(solver.indenter_displacement(), rezoned.displacement);
    if (!balanced.converged) {
      out.failure = "the new mesh did not come to equilibrium: " + balanced.reason;
      return out;
    }
    out.record.elements_after = static_cast<int>(rezoned.mesh.tets.size());
    out.record.force_after = std::accumulate(balanced.indenter_force.begin(), balanced.indenter_force.end(), 0.0);
    out.record.min_volume_ratio_after = balanced.min_volume_ratio;
    out.tissue = std::move(rezoned.mesh);
    out.solver = std::move(next);
  } catch (const std::exception& e) {
    out.failure = e.what();
  }
  out.record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace needlekit::insertion::detail
