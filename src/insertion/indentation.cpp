#include "needlekit/insertion/indentation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "needlekit/core/errors.hpp"
#include "needlekit/insertion/averaged_contact_pressure.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/cell_replication.hpp"
#include "needlekit/mesh/tet_count_estimate.hpp"
#include "needlekit/needle/rounded_edges.hpp"
#include "array_model.hpp"
#include "needle_loads.hpp"
#include "needle_outcomes.hpp"
#include "rezoning.hpp"

namespace needlekit::insertion {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double lowest_tip_height(const IndentationCase& indentation_case) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const NeedleSite& site : indentation_case.needles) lowest = std::min(lowest, site.tip_height);
  return lowest;
}

// The case's block with one insertion site per needle, as run_indentation meshes it.
mesh::LayeredBlockOptions block_to_mesh(const IndentationCase& c) {
  mesh::LayeredBlockOptions block = c.block;
  block.insertion_sites.clear();
  for (const NeedleSite& site : c.needles) block.insertion_sites.push_back(site.position);
  return block;
}

std::string um(double metres) { return fmt::format("{:.4g} um", metres * 1e6); }

// Pa, per needle of the model solved: p̄_l of the tissue nodes in contact with it (the averaged-pressure law; empty
// under the dissertation's).
std::vector<double> averaged_pressures(const fem::QuasiStaticSolver& solver, const IndentationCase& c,
                                       std::size_t needles) {
  if (c.puncture.criterion != PunctureLaw::AveragedPressure) return {};
  std::vector<std::vector<ContactPoint>> points(needles);
  const std::vector<int>& flag = solver.contact_flag();
  for (std::size_t a = 0; a < flag.size(); ++a) {
    if (flag[a] == 0) continue;
    const double area = solver.top_node_area()[a];
    points[static_cast<std::size_t>(flag[a] - 1)].push_back(
        {solver.nodes()[a], solver.contact_pressure()[a] * area, area});
  }
  std::vector<double> pressures;
  for (const std::vector<ContactPoint>& needle : points) {
    pressures.push_back(averaged_peak_pressure(needle, c.puncture.material_length));
  }
  return pressures;
}

IndentationStep step_of(const fem::StepResult& solved, double depth, const detail::NeedleLoads& loads,
                        std::vector<double> averaged_pressure) {
  IndentationStep step;
  step.depth = depth;
  step.needle_averaged_pressure = std::move(averaged_pressure);
  for (double p : step.needle_averaged_pressure) step.averaged_pressure = std::max(step.averaged_pressure, p);
  step.lateral_force = loads.lateral_force;
  step.moment = loads.moment;
  step.needle_force = solved.indenter_force;
  step.needle_contact_area = solved.contact_area;
  for (double f : solved.indenter_force) step.force += f;
  for (double a : solved.contact_area) step.contact_area += a;
  for (double p : solved.max_contact_pressure) step.max_contact_pressure = std::max(step.max_contact_pressure, p);
  for (int n : solved.contact_nodes) step.contact_nodes += n;
  step.contact_pressure = contact_pressure({depth, step.force, step.contact_area, 0.0});  // Eq 3.17: P_s = F/dA
  step.strain_energy = solved.strain_energy;
  step.newton_iterations = solved.newton_iterations;
  step.cutbacks = solved.cutbacks;
  step.factorizations = solved.factorizations;
  step.min_volume_ratio = solved.min_volume_ratio;
  step.tip_embedded_depth = solved.tip_embedded_depth;
  for (const fem::IterationRecord& iteration : solved.iterations) step.linear_iterations += iteration.linear_iterations;
  if (!solved.iterations.empty()) {
    step.max_residual = solved.iterations.front().residual_norm;
    step.final_residual = solved.iterations.back().residual_norm;
  }
  step.assembly_seconds = solved.assembly_seconds;
  step.solve_seconds = solved.solve_seconds;
  step.step_seconds = solved.total_seconds;
  return step;
}

// A criterion that fires at the first step has no earlier step to interpolate from: bisect the step from the
// undeformed state (no force, no contact: no criterion met) so that the point is located inside it, as between later
// steps. kFirstStepBisections halvings leave a bracket of 1/16 of the step, interpolated linearly. The solver is left
// in the state of the last bisection.
constexpr int kFirstStepBisections = 4;

PuncturePoint puncture_in_first_step(fem::QuasiStaticSolver& solver, const IndentationCase& c, double lowest,
                                     const PunctureSample& first, const PuncturePoint& fired) {
  PunctureSample below{0.0, 0.0, 0.0, 0.0};
  PunctureSample above = first;
  for (int i = 0; i < kFirstStepBisections; ++i) {
    const double middle = 0.5 * (below.depth + above.depth);
    const fem::StepResult solved = solver.advance_to(lowest + middle);
    if (!solved.converged) break;  // keep the bracket found so far
    const IndentationStep step = step_of(solved, middle, {}, averaged_pressures(solver, c, c.needles.size()));
    const PunctureSample sample{middle, step.force, step.contact_area, step.strain_energy, step.averaged_pressure};
    (puncture_point({sample}, c.puncture) ? above : below) = sample;
  }
  const std::optional<PuncturePoint> located = puncture_point({below, above}, c.puncture);
  return located ? *located : fired;
}

// How the needle mesh is placed over a site (the header's "Frames" and "Angled insertion"): tip-down by the
// half-turn about x, (x, y, z) -> (x, −y, z_tip − z) (a proper rotation: the outward orientation is kept), the tip's
// centre at the origin; turned and tilted (detail::needle_rotation); the tip's centre over the site and the lowest
// point of the needle (of its mesh with sharp edges, which holds the rounded one) at the site's tip height.
class NeedlePlacement {
 public:
  explicit NeedlePlacement(const IndentationCase& c) : rotation_(detail::needle_rotation(c)) {
    double bottom = std::numeric_limits<double>::infinity();
    tip_ = -bottom;
    for (const Eigen::Vector3d& v : c.needle.vertices) tip_ = std::max(tip_, v.z()), bottom = std::min(bottom, v.z());
    // The tip's (x, y): the centroid of the vertices on the tip (the axis for cylinders and cones, the tip face's
    // centre for bevels).
    int on_tip = 0;
    for (const Eigen::Vector3d& v : c.needle.vertices) {
      if (v.z() >= tip_ - 1e-9 * (tip_ - bottom)) {
        tip_centre_ += v.head<2>();
        ++on_tip;
      }
    }
    tip_centre_ /= std::max(on_tip, 1);
    lowest_ = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& v : c.needle.vertices) lowest_ = std::min(lowest_, turned(v).z());
  }
  // The needle-frame point v over `site`, m.
  Eigen::Vector3d operator()(const Eigen::Vector3d& v, const NeedleSite& site) const {
    const Eigen::Vector3d t = turned(v);
    return {t.x() + site.position.x(), t.y() + site.position.y(), t.z() - lowest_ + site.tip_height};
  }

 private:
  Eigen::Vector3d turned(const Eigen::Vector3d& v) const {
    return rotation_ * Eigen::Vector3d(v.x() - tip_centre_.x(), -(v.y() - tip_centre_.y()), tip_ - v.z());
  }
  Eigen::Matrix3d rotation_;
  Eigen::Vector2d tip_centre_ = Eigen::Vector2d::Zero();
  double tip_ = 0, lowest_ = 0;
};

// m: each needle's base centre (the needle frame's origin, on its axis) as placed at zero displacement.
std::vector<Eigen::Vector3d> placed_bases(const IndentationCase& c) {
  const NeedlePlacement place(c);
  std::vector<Eigen::Vector3d> bases;
  for (const NeedleSite& site : c.needles) bases.push_back(place(Eigen::Vector3d::Zero(), site));
  return bases;
}

// The warm start's field at `depth` (the same load step of the earlier run), if it has one of this mesh's size.
const std::vector<Eigen::Vector3d>* warm_start_at(const std::vector<StepDisplacement>* warm_start, double depth,
                                                  std::size_t nodes) {
  if (warm_start == nullptr) return nullptr;
  for (const StepDisplacement& step : *warm_start) {
    if (std::abs(step.depth - depth) <= 1e-12 * std::abs(depth) && step.displacement.size() == nodes) {
      return &step.displacement;
    }
  }
  return nullptr;
}

}  // namespace

std::string_view to_string(IndentationStatus status) { return name_of(kIndentationStatusNames, status); }

Eigen::Vector3d needle_axis(const IndentationCase& c) {
  return {std::sin(c.angle) * std::cos(c.azimuth), std::sin(c.angle) * std::sin(c.azimuth), -std::cos(c.angle)};
}

double effective_edge_radius(const IndentationCase& c) {
  if (!c.geometry || c.solver.contact != fem::ContactModel::Surface) return 0.0;
  return c.edge_radius.value_or(needle::default_edge_radius(*c.geometry));
}

bool uses_nodal_average(const IndentationCase& c) {
  // The mesher's layers: a given mesh's, else the block's (none: the default skin, as layered_block_mesh takes it).
  const std::vector<mesh::TissueLayer> layers =
      c.tissue_mesh ? c.tissue_mesh->layers : c.block.layers.empty() ? materials::skin_layers() : c.block.layers;
  return std::any_of(layers.begin(), layers.end(),
                     [&](const mesh::TissueLayer& l) { return fem::nodal_average_applies(c.solver, l.poisson_ratio); });
}

bool meshes_coarse_level(const IndentationCase& c) {
  if (c.tissue_mesh || c.solver.order != fem::ElementOrder::Linear) return false;
  if (c.solver.linear_solver == fem::LinearSolver::TwoGrid) return true;
  if (c.solver.linear_solver != fem::LinearSolver::Automatic) return false;
  return mesh::estimated_tetrahedra(block_to_mesh(c)) >= kTwoGridMinimumTetrahedra;
}

std::vector<fem::Indenter> placed_indenters(const IndentationCase& c) {
  const NeedlePlacement place(c);
  const double edge_radius = effective_edge_radius(c);
  geometry::TriangleMesh body = c.needle;  // with rounded edges the eroded core, in the same needle frame
  if (edge_radius > 0) {
    const needle::ErodedNeedle core = needle::eroded_needle(*c.geometry, edge_radius);
    body = needle::needle_surface_mesh(core.core, c.needle_mesh);
    for (Eigen::Vector3d& v : body.vertices) v.z() += core.base_offset;
  }
  std::vector<fem::Indenter> indenters;
  for (const NeedleSite& site : c.needles) {
    fem::Indenter indenter;
    indenter.surface = body;
    indenter.edge_radius = edge_radius;
    indenter.direction = needle_axis(c);
    for (Eigen::Vector3d& v : indenter.surface.vertices) v = place(v, site);
    indenters.push_back(std::move(indenter));
  }
  return indenters;
}

namespace {

// The run's progress: the stage and the fraction done, with the step count and depth of the result so far.
class ProgressReport {
public:
  ProgressReport(const IndentationCase& c, const IndentationOptions& options, const IndentationResult& result)
      : case_(c), options_(options), result_(result) {}
  void operator()(std::string_view stage, double fraction) const {
    if (!options_.progress) return;
    IndentationProgress progress;
    progress.stage = std::string(stage);
    progress.step = static_cast<int>(result_.steps.size());
    progress.steps = case_.steps;
    progress.depth = result_.steps.empty() ? 0.0 : result_.steps.back().depth;
    progress.fraction = std::clamp(fraction, 0.0, 1.0);
    options_.progress(progress);
  }

private:
  const IndentationCase& case_;
  const IndentationOptions& options_;
  const IndentationResult& result_;
};

struct MeshedTissue {
  mesh::TetMesh tissue;
  std::optional<mesh::CoarseLevel> coarse;  // the block's coarse level, if meshed with one (the two-grid solver)
};

// The case's tissue mesh, or the block of the model solved `m` meshed here (its quality and time into result).
MeshedTissue tissue_of(const IndentationCase& c, const IndentationCase& m, const ProgressReport& report,
                       IndentationResult& result) {
  MeshedTissue meshed;
  if (c.tissue_mesh) {
    meshed.tissue = *c.tissue_mesh;
    result.elements = static_cast<int>(meshed.tissue.tets.size());
    return meshed;
  }
  report("mesh", 0.0);
  mesh::LayeredBlockOptions block = block_to_mesh(m);
  block.coarse_level = meshes_coarse_level(m);
  const Clock::time_point mesh_start = Clock::now();
  // An array's block (or its reduced model's) from copies of one cell where they fit: a needle's square, or a
  // hexagonal array's pair of rows (mesh/cell_replication.hpp; a fallback to the whole block is reported by
  // io::indentation_scale_warnings).
  mesh::LayeredBlockResult block_mesh =
      c.array && m.needles.size() > 1 ? mesh::array_block_mesh(block, cell_lattice(*c.array)).block
                                      : mesh::layered_block_mesh(block);
  meshed.tissue = std::move(block_mesh.mesh);
  meshed.coarse = std::move(block_mesh.coarse);
  result.quality = std::move(block_mesh.quality);
  result.mesh_seconds = seconds_since(mesh_start);  // everything: geometry, meshing, quality, conversion
  result.elements = static_cast<int>(meshed.tissue.tets.size());
  return meshed;
}

// A converged (or partly converged) step added to the result, with the needles' external work, trapezoidal over
// the converged steps.
void add_step(IndentationStep step, double step_seconds, IndentationResult& result) {
  const double previous_depth = result.steps.empty() ? 0.0 : result.steps.back().depth;
  const double previous_force = result.steps.empty() ? 0.0 : result.steps.back().force;
  const double previous_work = result.steps.empty() ? 0.0 : result.steps.back().external_work;
  step.external_work = previous_work + 0.5 * (previous_force + step.force) * (step.depth - previous_depth);
  step.step_seconds = step_seconds;  // wall time of the whole step (the solver's own total leaves out its set-up)
  result.steps.push_back(step);
}

// The status and reason of a run that did not fail: punctured (the first needle's, with an array the fraction
// punctured) or reached the depth.
void set_outcome(const IndentationCase& c, IndentationResult& result) {
  if (!result.puncture) {
    result.status = IndentationStatus::ReachedDepth;
    result.reason = fmt::format("reached the final depth {} without puncture{}", um(c.depth),
                                c.puncture.critical_pressure || c.puncture.toughness ? ""
                                                                                      : " (no puncture criterion given)");
    return;
  }
  const std::string after = result.reason;  // the solver's failure after the puncture, if any
  result.status = IndentationStatus::Punctured;
  const double fraction = result.array ? result.array->punctured_fraction.back() : 1.0;
  result.reason = fmt::format("the {} criterion fired at depth {} (force {:.4g} N){}{}{}",
                              to_string(result.puncture->criterion), um(result.puncture->depth),
                              result.puncture->force,
                              result.array ? fmt::format(" under the first needle; {:.4g} % of the {} needles "
                                                         "punctured by depth {}",
                                                         100 * fraction, c.needles.size(),
                                                         um(result.steps.back().depth))
                                           : "",
                              c.stop_at_puncture ? "" : fmt::format("; continued to {}", um(c.depth)), after);
}

// What the solver was set up with: its nodes, free dofs, linear solver and nodal-averaged elements.
void describe_solver(const fem::QuasiStaticSolver& solver, IndentationResult& result) {
  result.nodes = static_cast<int>(solver.nodes().size());
  result.dofs = solver.free_dof_count();
  result.linear_solver = solver.linear_solver();
  result.nodal_average_elements = solver.nodal_average_elements();
}

// The step solved at `depth` on the model `m` of the case `c`, as the whole case's step.
IndentationStep whole_case_step(const fem::QuasiStaticSolver& solver, const fem::StepResult& solved, double depth,
                                const IndentationCase& c, const IndentationCase& m,
                                const std::vector<Eigen::Vector3d>& bases, const detail::ArrayModel& array_model) {
  return detail::whole_step(step_of(solved, depth, detail::needle_loads(solved, needle_axis(c), bases),
                                    averaged_pressures(solver, m, m.needles.size())),
                            array_model);
}

// Why load step k failed, and which steps are kept (with a partly converged step, its deepest converged state).
std::string failed_step_reason(const IndentationCase& c, int k, double depth, const std::string& solver_reason,
                               std::size_t completed, bool partial, double reached) {
  return fmt::format("load step {} of {} (to depth {}) did not converge: {}; {} completed step{} kept{}", k, c.steps,
                     um(depth), solver_reason, completed, completed == 1 ? "" : "s",
                     partial ? fmt::format(", the last one the step's deepest converged state at {}", um(reached)) : "");
}

// The run's puncture after a step: with an array the first needle's (each needle by its own samples), else the
// criteria on the samples so far (found in the first step: bisected within it).
void update_puncture(const IndentationCase& c, fem::QuasiStaticSolver& solver, double lowest,
                     const std::vector<PunctureSample>& samples, const detail::NeedleRecorder& needles,
                     IndentationResult& result) {
  if (c.array) {
    result.puncture = needles.first_puncture(result.steps);
  } else if (!result.puncture) {
    result.puncture = puncture_point(samples, c.puncture);
    if (result.puncture && samples.size() == 1)
      result.puncture = puncture_in_first_step(solver, c, lowest, samples.front(), *result.puncture);
  }
}

// The case's solver options for the model `m` solved (its boundary), reporting Newton's iterations as progress
// within the current step. `report` and `lowest` (m, the needles' travel to the surface) outlive the options.
fem::SolverOptions solver_options_of(const IndentationCase& c, const IndentationCase& m,
                                     const IndentationOptions& options, const ProgressReport& report,
                                     const double& lowest) {
  fem::SolverOptions solver_options = c.solver;
  if (options.progress) {
    const auto user_progress = c.solver.progress;
    solver_options.progress = [&c, &report, &lowest, user_progress](const fem::SolverProgress& p) {
      if (user_progress) user_progress(p);
      report("step", (p.target_displacement - lowest) / c.depth - 0.5 / c.steps);
    };
  }
  solver_options.boundary = m.solver.boundary;
  return solver_options;
}

}  // namespace

IndentationResult run_indentation(const IndentationCase& c, const IndentationOptions& options) {
  const Clock::time_point start = Clock::now();
  validate(c);
  IndentationResult result;
  const ProgressReport report(c, options, result);
  const detail::ArrayModel array_model = detail::array_model(c);
  const IndentationCase& m = array_model.reduced ? *array_model.reduced : c;  // the model solved
  const MeshedTissue meshed = tissue_of(c, m, report, result);
  if (options.on_mesh) options.on_mesh(meshed.tissue);

  report("setup", 0.0);
  const Clock::time_point setup_start = Clock::now();
  const double lowest = detail::travel_to_surface(c, lowest_tip_height(c));  // m, along the needle's axis
  const fem::SolverOptions solver_options = solver_options_of(c, m, options, report, lowest);
  fem::QuasiStaticSolver solver(meshed.tissue, placed_indenters(m), solver_options,
                                meshed.coarse ? &*meshed.coarse : nullptr);
  const std::vector<Eigen::Vector3d> bases = placed_bases(m);
  describe_solver(solver, result);
  result.setup_seconds = seconds_since(setup_start);

  std::vector<PunctureSample> samples;
  detail::NeedleRecorder needles(c);
  detail::RezonableTissue tissue(m, solver_options, meshed.tissue, array_model.factor);
  bool failed = false;
  for (int k = 1; k <= c.steps; ++k) {
    const double depth = c.depth * k / c.steps;
    const Clock::time_point step_start = Clock::now();
    const std::vector<Eigen::Vector3d>* start = warm_start_at(options.warm_start, depth, solver.nodes().size());
    result.warm_started_steps += start != nullptr;
    const fem::StepResult solved = start ? solver.advance_to(lowest + depth, *start) : solver.advance_to(lowest + depth);
    const double step_seconds = seconds_since(step_start);
    // A step that failed after some of its cut-back substeps converged leaves the solver in the deepest converged
    // state inside the step: kept as a last, shorter step (and searched for puncture), so that the run reports the
    // depth it reached, not the end of the step before.
    const double reached = solved.indenter_displacement - lowest;
    const double kept = result.steps.empty() ? 0.0 : result.steps.back().depth;
    const bool partial = !solved.converged && reached > kept + 1e-9 * c.depth;
    if (!solved.converged && tissue.rezoned_after_failure(solver, k, reached, solved.reason, options, result)) {
      --k;  // the step again, on the new mesh
      continue;
    }
    if (!solved.converged) {
      failed = true;
      result.status = IndentationStatus::SolverFailed;
      result.reason =
          failed_step_reason(c, k, depth, solved.reason, result.steps.size() + (partial ? 1 : 0), partial, reached);
      if (!partial) break;
    }
    const double step_depth = partial ? reached : depth;
    add_step(whole_case_step(solver, solved, step_depth, c, m, bases, array_model), step_seconds, result);
    const IndentationStep& step = result.steps.back();
    if (options.keep_displacements) result.displacements.push_back({step_depth, solver.displacement()});
    if (options.on_step) options.on_step(step, solver);
    report("step", static_cast<double>(k) / c.steps);
    samples.push_back({step.depth, step.force, step.contact_area, step.strain_energy, step.averaged_pressure});
    needles.add(step);
    update_puncture(c, solver, lowest, samples, needles, result);
    if (partial) {
      // Punctured before the solver gave up: with stop_at_puncture that is the run's outcome (finer load steps
      // would have stopped there); the failure stays in the reason.
      if (result.puncture && c.stop_at_puncture) {
        failed = false;
        result.reason = fmt::format("; the solver then failed: {}", result.reason);
      }
      break;
    }
    if (result.puncture && c.stop_at_puncture && (!c.array || needles.all_punctured())) break;
    if (k < c.steps) tissue.rezone_if_crushed(solver, k, options, result);
  }
  result.needles = needles.needles();
  result.bending = detail::bending_check(c, result.steps);
  if (c.array) result.array = needles.array_outcome(result.steps);
  if (!failed) set_outcome(c, result);
  result.total_seconds = seconds_since(start);
  return result;
}

PrePunctureCurve pre_puncture_curve(const IndentationResult& result) {
  PrePunctureCurve curve;
  curve.curve.depth.push_back(0.0);
  curve.curve.force.push_back(0.0);
  for (const IndentationStep& step : result.steps) {
    curve.curve.depth.push_back(step.depth);
    curve.curve.force.push_back(step.force);
  }
  curve.puncture = result.puncture;
  return curve;
}

}  // namespace needlekit::insertion
