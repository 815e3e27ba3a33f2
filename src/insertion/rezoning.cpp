#include "rezoning.hpp"

#include <fmt/format.h>

#include <chrono>
#include <exception>
#include <numeric>

#include "needlekit/mesh/rezoned_mesh.hpp"

namespace needlekit::insertion::detail {

Rezoning rezoned(const mesh::TetMesh& tissue, const fem::QuasiStaticSolver& solver,
                 std::vector<fem::Indenter> indenters, const fem::SolverOptions& options, double step_force,
                 double step_volume_ratio, double force_factor) {
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
    if (const auto history = solver.contact_history()) next->set_contact_history(*history);
    const fem::StepResult balanced = next->advance_to(solver.indenter_displacement(), rezoned.displacement, false);
    if (balanced.converged) {
      out.record.balance = balanced.start_balance;
      out.record.elements_after = static_cast<int>(rezoned.mesh.tets.size());
      out.record.force_after =
          force_factor * std::accumulate(balanced.indenter_force.begin(), balanced.indenter_force.end(), 0.0);
      out.record.min_volume_ratio_after = balanced.min_volume_ratio;
      out.tissue = std::move(rezoned.mesh);
      out.solver = std::move(next);
    } else {  // the time it took is reported too
      out.record.failure = "the new mesh did not come to equilibrium: " + balanced.reason;
    }
  } catch (const std::exception& e) {
    out.record.failure = e.what();
  }
  out.record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

bool RezonableTissue::rezoned_after_failure(fem::QuasiStaticSolver& solver, int k, double depth,
                                            const std::string& why, const IndentationOptions& options,
                                            IndentationResult& result) {
  if (!allowed(result)) return false;
  const IndentationStep* last = result.steps.empty() ? nullptr : &result.steps.back();
  return rezone(solver, k - 1, depth, last ? last->force : 0, last ? last->min_volume_ratio : 1,
                fmt::format("load step {} failed: {}", k, why), options, result);
}

void RezonableTissue::rezone_if_crushed(fem::QuasiStaticSolver& solver, int k, const IndentationOptions& options,
                                        IndentationResult& result) {
  const IndentationStep& step = result.steps.back();
  if (!allowed(result) || step.min_volume_ratio >= options_.rezone_volume_ratio) return;
  rezone(solver, k, step.depth, step.force, step.min_volume_ratio,
         fmt::format("the smallest J = det F fell to {:.3g} (below rezone_volume_ratio {:.3g})",
                     step.min_volume_ratio, options_.rezone_volume_ratio),
         options, result);
}

bool RezonableTissue::allowed(const IndentationResult& result) const {
  return options_.rezone && static_cast<int>(result.remeshes.size()) < options_.max_remeshes;
}

bool RezonableTissue::rezone(fem::QuasiStaticSolver& solver, int step, double depth, double force,
                             double min_volume_ratio, std::string reason, const IndentationOptions& options,
                             IndentationResult& result) {
  Rezoning rezoning =
      rezoned(current(), solver, placed_indenters(m_), options_, force, min_volume_ratio, force_factor_);
  rezoning.record.step = step;
  rezoning.record.depth = depth;
  rezoning.record.reason = std::move(reason);
  result.remeshes.push_back(rezoning.record);
  if (options.on_remesh) options.on_remesh(result.remeshes.back());
  if (!rezoning.solver) return false;
  rezoned_ = std::move(rezoning.tissue);
  solver = std::move(*rezoning.solver);
  if (options.on_mesh) options.on_mesh(*rezoned_);
  return true;
}

}  // namespace needlekit::insertion::detail
