#include "needlekit/insertion/indentation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "needlekit/core/errors.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/tet_count_estimate.hpp"
#include "needlekit/needle/rounded_edges.hpp"
#include "array_model.hpp"
#include "needle_loads.hpp"
#include "needle_outcomes.hpp"

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

IndentationStep step_of(const fem::StepResult& solved, double depth, const detail::NeedleLoads& loads) {
  IndentationStep step;
  step.depth = depth;
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
    const IndentationStep step = step_of(solved, middle, {});
    const PunctureSample sample{middle, step.force, step.contact_area, step.strain_energy};
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

// loading.angle and loading.azimuth: finite, 0 <= angle < 90 deg, and a tilt only with true contact and without
// a reduced array model (its symmetry planes assume vertical needles).
void validate_angle(const IndentationCase& c) {
  const double degrees = c.angle * 180 / M_PI;
  if (!std::isfinite(c.angle) || !(c.angle >= 0 && c.angle < M_PI / 2)) {
    throw InvalidInput(fmt::format("loading.angle: {:.6g} deg is outside [0, 90) deg, expected the needle's axis "
                                   "from the skin's normal, 0 <= angle < 90 deg",
                                   degrees));
  }
  if (!std::isfinite(c.azimuth)) {
    throw InvalidInput("loading.azimuth: not finite, expected an angle in the block's x-y plane from +x");
  }
  if (c.angle == 0) return;
  if (c.solver.contact != fem::ContactModel::Surface) {
    throw InvalidInput(fmt::format("loading.angle: {:.6g} deg with contact = \"tip-nodes\", whose nodes follow a flat "
                                   "tip straight down; expected angle = \"0 deg\" or model.contact = \"surface\"",
                                   degrees));
  }
  if (c.array && c.array->symmetry != ArraySymmetry::None) {
    throw InvalidInput(fmt::format("loading.angle: {:.6g} deg with array.symmetry = \"{}\", whose symmetry planes "
                                   "need vertical needles; expected angle = \"0 deg\" or no array.symmetry",
                                   degrees, name_of(kArraySymmetryNames, c.array->symmetry)));
  }
}

}  // namespace

double tissue_height(const IndentationCase& c) {
  if (c.tissue_mesh) {
    double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : c.tissue_mesh->nodes) top = std::max(top, p.z()), bottom = std::min(bottom, p.z());
    return c.tissue_mesh->nodes.empty() ? 0.0 : top - bottom;
  }
  double height = 0;
  for (const mesh::TissueLayer& layer : c.block.layers) height += layer.thickness;
  return height;
}

std::string to_string(IndentationStatus status) {
  switch (status) {
    case IndentationStatus::Punctured: return "punctured";
    case IndentationStatus::ReachedDepth: return "reached-depth";
    case IndentationStatus::SolverFailed: return "solver-failed";
  }
  return "unknown";
}

void validate(const IndentationCase& c) {
  if (c.needle.triangles.empty() || c.needle.vertices.empty()) {
    throw InvalidInput("needle: the needle surface mesh is empty, expected a closed triangle mesh");
  }
  if (c.edge_radius) {
    if (!c.geometry) {
      throw InvalidInput("needle.edge_radius: given for a needle given as a mesh, whose edges are the mesh's; "
                         "expected edge_radius only with a parametric needle (shape, tip_diameter, ...)");
    }
    if (c.solver.contact != fem::ContactModel::Surface) {
      throw InvalidInput("needle.edge_radius: given with contact = \"tip-nodes\", which takes the tip face as flat; "
                         "expected contact = \"surface\" or no edge_radius");
    }
  }
  if (c.geometry && c.solver.contact == fem::ContactModel::Surface) {
    needle::eroded_needle(*c.geometry, effective_edge_radius(c));  // throws for a radius outside its range
  }
  if (c.needles.empty()) throw InvalidInput("needles: no needle, expected at least one insertion site");
  detail::validate_array_case(c);
  for (std::size_t i = 0; i < c.needles.size(); ++i) {
    const NeedleSite& site = c.needles[i];
    if (!site.position.allFinite()) {
      throw InvalidInput(fmt::format("needles[{}]: the position is not finite, expected finite x and y", i));
    }
    if (!std::isfinite(site.tip_height) || site.tip_height < 0) {
      throw InvalidInput(fmt::format("needles[{}].tip_height: {} is below the surface: the needle would start inside "
                                     "the tissue, expected a tip height >= 0",
                                     i, um(site.tip_height)));
    }
    if (!c.tissue_mesh && !(std::abs(site.position.x()) < c.block.width / 2 &&
                            std::abs(site.position.y()) < c.block.length / 2)) {
      throw InvalidInput(fmt::format("needles[{}]: ({}, {}) is outside the {} x {} block, expected |x| < width/2 and "
                                     "|y| < length/2",
                                     i, um(site.position.x()), um(site.position.y()), um(c.block.width),
                                     um(c.block.length)));
    }
  }
  if (!std::isfinite(c.depth) || !(c.depth > 0)) {
    throw InvalidInput(fmt::format("loading.depth: {} is not positive, expected a depth > 0", um(c.depth)));
  }
  validate_angle(c);
  const double height = tissue_height(c);
  if (height > 0 && !(c.depth * std::cos(c.angle) < height)) {
    throw InvalidInput(fmt::format("loading.depth: {} reaches through the {} high tissue block, expected a depth below "
                                   "its height (tissue.height or the layers' thicknesses){}",
                                   um(c.depth), um(height), c.angle > 0 ? " over the cosine of loading.angle" : ""));
  }
  if (!c.tissue_mesh) {  // the mesh sizes under the case file's keys (the CLI's overrides land here too)
    for (const auto& [key, size] : {std::pair{"mesh.size_at_tip", c.block.size_at_site},
                                    std::pair{"mesh.size_far", c.block.size_far}}) {
      if (!std::isfinite(size) || !(size > 0)) {
        throw InvalidInput(fmt::format("{}: {} is not positive, expected a size > 0", key, um(size)));
      }
    }
    if (c.block.size_far < c.block.size_at_site) {
      throw InvalidInput(fmt::format("mesh.size_far: {} is smaller than mesh.size_at_tip = {}, expected size_far >= "
                                     "size_at_tip",
                                     um(c.block.size_far), um(c.block.size_at_site)));
    }
  }
  if (c.solver.linear_solver == fem::LinearSolver::TwoGrid && c.solver.order == fem::ElementOrder::Linear &&
      c.tissue_mesh) {
    throw InvalidInput(
        "solver.linear_solver: \"two-grid\" with linear elements needs a block meshed here (its coarse "
        "level is the block meshed at coarser sizes), not a tissue mesh file; expected another "
        "linear_solver, or quadratic elements");
  }
  if (c.steps < 1) throw InvalidInput(fmt::format("loading.steps: {} is not >= 1, expected at least one step", c.steps));
  c.solver.validate();
  validate(c.puncture);
}

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

IndentationResult run_indentation(const IndentationCase& c, const IndentationOptions& options) {
  const Clock::time_point start = Clock::now();
  validate(c);
  IndentationResult result;
  auto report = [&](std::string_view stage, double fraction) {
    if (!options.progress) return;
    IndentationProgress progress;
    progress.stage = std::string(stage);
    progress.step = static_cast<int>(result.steps.size());
    progress.steps = c.steps;
    progress.depth = result.steps.empty() ? 0.0 : result.steps.back().depth;
    progress.fraction = std::clamp(fraction, 0.0, 1.0);
    options.progress(progress);
  };

  const detail::ArrayModel array_model = detail::array_model(c);
  const IndentationCase& m = array_model.reduced ? *array_model.reduced : c;  // the model solved
  mesh::TetMesh tissue;
  std::optional<mesh::CoarseLevel> coarse;  // the block's coarse level, if meshed with one (the two-grid solver)
  if (c.tissue_mesh) {
    tissue = *c.tissue_mesh;
  } else {
    report("mesh", 0.0);
    mesh::LayeredBlockOptions block = block_to_mesh(m);
    block.coarse_level = meshes_coarse_level(m);
    const Clock::time_point mesh_start = Clock::now();
    mesh::LayeredBlockResult meshed = mesh::layered_block_mesh(block);
    tissue = std::move(meshed.mesh);
    coarse = std::move(meshed.coarse);
    result.quality = std::move(meshed.quality);
    result.mesh_seconds = seconds_since(mesh_start);  // everything: geometry, meshing, quality, conversion
  }
  result.elements = static_cast<int>(tissue.tets.size());
  if (options.on_mesh) options.on_mesh(tissue);

  report("setup", 0.0);
  const Clock::time_point setup_start = Clock::now();
  const double lowest = detail::travel_to_surface(c, lowest_tip_height(c));  // m, along the needle's axis
  fem::SolverOptions solver_options = c.solver;
  if (options.progress) {  // Newton iterations move the bar within the current step
    const auto user_progress = c.solver.progress;
    solver_options.progress = [&, user_progress](const fem::SolverProgress& p) {
      if (user_progress) user_progress(p);
      report("step", (p.target_displacement - lowest) / c.depth - 0.5 / c.steps);
    };
  }
  solver_options.boundary = m.solver.boundary;
  fem::QuasiStaticSolver solver(tissue, placed_indenters(m), solver_options, coarse ? &*coarse : nullptr);
  const std::vector<Eigen::Vector3d> bases = placed_bases(m);
  result.nodes = static_cast<int>(solver.nodes().size());
  result.dofs = solver.free_dof_count();
  result.linear_solver = solver.linear_solver();
  result.nodal_average_elements = solver.nodal_average_elements();
  result.setup_seconds = seconds_since(setup_start);

  std::vector<PunctureSample> samples;
  detail::NeedleRecorder needles(c);
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
    if (!solved.converged) {
      failed = true;
      result.status = IndentationStatus::SolverFailed;
      const std::size_t completed = result.steps.size() + (partial ? 1 : 0);
      result.reason = fmt::format("load step {} of {} (to depth {}) did not converge: {}; {} completed step{} kept{}",
                                  k, c.steps, um(depth), solved.reason, completed, completed == 1 ? "" : "s",
                                  partial ? fmt::format(", the last one the step's deepest converged state at {}",
                                                        um(reached))
                                          : "");
      if (!partial) break;
    }
    const double step_depth = partial ? reached : depth;
    IndentationStep step = detail::whole_step(step_of(solved, step_depth, detail::needle_loads(solved, needle_axis(c), bases)),
                                              array_model);
    // External work of the needles, trapezoidal over the converged steps (the needles move only along z).
    const double previous_depth = result.steps.empty() ? 0.0 : result.steps.back().depth;
    const double previous_force = result.steps.empty() ? 0.0 : result.steps.back().force;
    const double previous_work = result.steps.empty() ? 0.0 : result.steps.back().external_work;
    step.external_work = previous_work + 0.5 * (previous_force + step.force) * (step_depth - previous_depth);
    step.step_seconds = step_seconds;  // wall time of the whole step (the solver's own total leaves out its set-up)
    result.steps.push_back(step);
    if (options.keep_displacements) result.displacements.push_back({step_depth, solver.displacement()});
    if (options.on_step) options.on_step(step, solver);
    report("step", static_cast<double>(k) / c.steps);
    samples.push_back({step.depth, step.force, step.contact_area, step.strain_energy});
    needles.add(step);
    if (c.array) {  // per needle: the first needle's puncture
      result.puncture = needles.first_puncture(result.steps);
    } else if (!result.puncture) {
      result.puncture = puncture_point(samples, c.puncture);
      if (result.puncture && samples.size() == 1)
        result.puncture = puncture_in_first_step(solver, c, lowest, samples.front(), *result.puncture);
    }
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
  }
  result.needles = needles.needles();
  result.bending = detail::bending_check(c, result.steps);
  if (c.array) result.array = needles.array_outcome(result.steps);
  if (!failed) {
    if (result.puncture) {
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
    } else {
      result.status = IndentationStatus::ReachedDepth;
      result.reason = fmt::format("reached the final depth {} without puncture{}", um(c.depth),
                                  c.puncture.critical_pressure || c.puncture.toughness
                                      ? ""
                                      : " (no puncture criterion given)");
    }
  }
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
