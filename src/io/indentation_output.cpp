#include "needlekit/io/indentation_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/io/array_output.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/insertion/loading_parameters.hpp"
#include "needlekit/insertion/puncture_parameters.hpp"
#include "needlekit/io/json_text.hpp"
#include "needlekit/io/parameter_json.hpp"
#include "needlekit/mesh/layered_block_parameters.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/io/scale_warnings.hpp"

namespace needlekit::io {
namespace {

nlohmann::json number_or_null(const std::optional<double>& value, double scale) {
  return value ? nlohmann::json(*value * scale) : nlohmann::json(nullptr);
}

// One object per rezoning (IndentationResult::remeshes).
nlohmann::json remeshes_json(const insertion::IndentationResult& result) {
  nlohmann::json remeshes = nlohmann::json::array();
  for (const insertion::Remesh& r : result.remeshes) {
    remeshes.push_back({{"step", r.step}, {"depth_um", r.depth * 1e6}, {"reason", r.reason},
                        {"failure", r.failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.failure)},
                        {"elements_before", r.elements_before}, {"elements_after", r.elements_after},
                        {"force_before_N", r.force_before}, {"force_after_N", r.force_after},
                        {"force_jump_percent", r.failure.empty() ? nlohmann::json(100 * r.force_jump()) : nlohmann::json(nullptr)},
                        {"min_volume_ratio_before", r.min_volume_ratio_before},
                        {"min_volume_ratio_after", r.min_volume_ratio_after}, {"seconds", r.seconds},
                        {"balance", r.failure.empty() ? nlohmann::json(fem::to_string(r.balance)) : nlohmann::json(nullptr)}});
  }
  return remeshes;
}

}  // namespace

VtuGrid indentation_grid(const fem::QuasiStaticSolver& solver, const mesh::TetMesh& tissue) {
  VtuGrid grid;
  grid.points = solver.nodes();
  const auto& elements = solver.elements();
  if (elements.size() != tissue.tets.size()) {
    throw InvalidInput(fmt::format("indentation grid: the solver has {} elements but the tissue mesh {} tetrahedra, "
                                   "expected the mesh the solver was built from",
                                   elements.size(), tissue.tets.size()));
  }
  grid.cells = elements;
  grid.cell_types.reserve(elements.size());
  for (const auto& element : elements) {
    grid.cell_types.push_back(element.size() == 10 ? VtkCellType::QuadraticTetra : VtkCellType::Tetra);
  }

  VtuField displacement{"displacement_m", 3, {}};
  displacement.values.reserve(3 * grid.points.size());
  for (const Eigen::Vector3d& u : solver.displacement()) displacement.values.insert(displacement.values.end(), {u.x(), u.y(), u.z()});
  VtuField flag{"contact_flag", 1, {}};
  for (int f : solver.contact_flag()) flag.values.push_back(f);
  VtuField pressure{"contact_pressure_Pa", 1, solver.contact_pressure()};
  grid.point_fields = {std::move(displacement), std::move(flag), std::move(pressure)};

  const fem::ElementFields fields = solver.element_fields();
  VtuField cauchy{"cauchy_stress_Pa", 9, {}};
  cauchy.values.reserve(9 * fields.cauchy_stress.size());
  for (const Eigen::Matrix3d& s : fields.cauchy_stress) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) cauchy.values.push_back(s(i, j));
    }
  }
  VtuField layer{"layer_id", 1, {}}, modulus{"youngs_modulus_Pa", 1, {}}, ratio{"poisson_ratio", 1, {}};
  for (int id : tissue.tet_layer) {
    layer.values.push_back(id);
    modulus.values.push_back(tissue.layers[id].youngs_modulus);
    ratio.values.push_back(tissue.layers[id].poisson_ratio);
  }
  grid.cell_fields = {std::move(cauchy),
                      {"von_mises_stress_Pa", 1, fields.von_mises_stress},
                      {"strain_energy_density_J_per_m3", 1, fields.strain_energy_density},
                      std::move(layer),
                      std::move(modulus),
                      std::move(ratio)};
  return grid;
}

VtuGrid needle_grid(const insertion::IndentationCase& indentation_case, double indenter_displacement) {
  VtuGrid grid;
  VtuField needle{"needle_id", 1, {}};
  int id = 0;
  // A reduced array model shows the needles it solves, on its reduced block.
  const bool reduced = indentation_case.array && indentation_case.array->symmetry != insertion::ArraySymmetry::None;
  for (const fem::Indenter& indenter : insertion::placed_indenters(
           reduced ? insertion::modelled_case(indentation_case) : indentation_case)) {
    const int offset = static_cast<int>(grid.points.size());
    const Eigen::Vector3d shift = indenter_displacement * indenter.direction.normalized();
    for (const Eigen::Vector3d& v : indenter.surface.vertices) grid.points.push_back(v + shift);
    for (const auto& t : indenter.surface.triangles) {
      grid.cells.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
      grid.cell_types.push_back(VtkCellType::Triangle);
      needle.values.push_back(id);
    }
    ++id;
  }
  grid.cell_fields.push_back(std::move(needle));
  return grid;
}

std::string force_depth_csv(const insertion::IndentationResult& result) {
  std::ostringstream out;
  out << "depth_um,force_N,contact_area_um2,contact_pressure_MPa,max_contact_pressure_MPa,contact_nodes,"
         "strain_energy_J,external_work_J,lateral_force_x_N,lateral_force_y_N,moment_Nm\n";
  out << "0,0,0,0,0,0,0,0,0,0,0\n";
  for (const insertion::IndentationStep& s : result.steps) {
    out << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", s.depth * 1e6,
                       s.force, s.contact_area * 1e12, s.contact_pressure * 1e-6, s.max_contact_pressure * 1e-6,
                       s.contact_nodes, s.strain_energy, s.external_work, s.lateral_force.x(), s.lateral_force.y(),
                       s.moment.norm());
  }
  return out.str();
}

std::string remesh_note(const insertion::Remesh& r) {
  return r.failure.empty()
             ? fmt::format("rezoned at {:g} um (after load step {}; {}): {} -> {} tetrahedra, force {:.4g} -> {:.4g} N "
                           "({:+.2f} %), smallest J {:.3g} -> {:.3g}, balance: {}",
                           r.depth * 1e6, r.step, r.reason, r.elements_before, r.elements_after, r.force_before,
                           r.force_after, 100 * r.force_jump(), r.min_volume_ratio_before, r.min_volume_ratio_after,
                           fem::to_string(r.balance))
             : fmt::format("rezoning at {:g} um (after load step {}; {}) failed: {}", r.depth * 1e6, r.step, r.reason,
                           r.failure);
}

std::vector<std::string> indentation_result_notes(const insertion::IndentationCase& c,
                                                  const insertion::IndentationResult& result) {
  std::vector<std::string> notes;
  for (const insertion::Remesh& r : result.remeshes) notes.push_back(remesh_note(r));
  for (std::string& note : deformation_notes(c, result)) notes.push_back(std::move(note));
  return notes;
}

std::vector<std::string> deformation_notes(const insertion::IndentationCase& c,
                                           const insertion::IndentationResult& result) {
  std::vector<std::string> notes;
  const double element = c.block.size_at_site;  // the tissue's element size at the tips
  const auto embedded = std::find_if(result.steps.begin(), result.steps.end(), [element](const auto& s) {
    return s.tip_embedded_depth > element;
  });
  if (embedded != result.steps.end()) {
    double deepest = 0;
    for (const insertion::IndentationStep& s : result.steps) deepest = std::max(deepest, s.tip_embedded_depth);
    notes.push_back(fmt::format(
        "from {:g} um deep a needle's tip lies inside the tissue, up to {:.3g} um past its top surface (more than the "
        "mesh's {:g} um at the tip): node-to-surface contact lets the tip's edges cut between the tissue's nodes, so "
        "the forces from there on are those of a partly embedded needle (frictionless, a narrow tip can pass through "
        "and the force fall to a few per cent); expected a finer [mesh] size_at_tip",
        embedded->depth * 1e6, deepest * 1e6, element * 1e6));
  }
  const auto crushed = std::find_if(result.steps.begin(), result.steps.end(), [](const insertion::IndentationStep& s) {
    return s.min_volume_ratio < insertion::kCrushedVolumeRatio;
  });
  if (crushed == result.steps.end()) return notes;
  double smallest = 1;
  for (const insertion::IndentationStep& s : result.steps) smallest = std::min(smallest, s.min_volume_ratio);
  notes.push_back(fmt::format("from {:g} um deep a tetrahedron is crushed to less than {:g} of its volume (smallest volume "
                      "ratio {:.3g}): the forces from there on depend on the mesh, and Newton may slow down; expected a "
                      "finer [mesh] size_at_tip, [model] contact = \"surface\" (the tip-node rule is a point load), "
                      "[solver] rezone = true or a shallower [loading] depth",
                      crushed->depth * 1e6, insertion::kCrushedVolumeRatio, smallest));
  return notes;
}

std::string solver_statistics_csv(const insertion::IndentationResult& result) {
  std::ostringstream out;
  out << "step,depth_um,newton_iterations,cutbacks,factorizations,cg_iterations,first_residual_N,final_residual_N,"
         "min_volume_ratio,assembly_s,solve_s,step_s\n";
  for (std::size_t k = 0; k < result.steps.size(); ++k) {
    const insertion::IndentationStep& s = result.steps[k];
    out << fmt::format("{},{:.9g},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", k + 1, s.depth * 1e6,
                       s.newton_iterations, s.cutbacks, s.factorizations, s.linear_iterations, s.max_residual,
                       s.final_residual, s.min_volume_ratio, s.assembly_seconds, s.solve_seconds, s.step_seconds);
  }
  return out.str();
}

nlohmann::json fe_models_json(const insertion::IndentationCase& c) {
  const fem::SolverOptions& solver = c.solver;
  return {{"law", fem::to_string(solver.law)},
          {"element", fem::to_string(solver.order)},
          {"contact", fem::to_string(solver.contact)},
          {"boundary", fem::to_string(solver.boundary)},
          {"volumetric", fem::to_string(solver.volumetric)},
          {"volumetric_stabilization_per_shear_modulus", solver.volumetric_stabilization},
          {"edge_radius_um", insertion::effective_edge_radius(c) * 1e6}};
}

std::string fe_models_text(const insertion::IndentationCase& c) {
  const fem::SolverOptions& solver = c.solver;
  const double edge_radius = insertion::effective_edge_radius(c);
  return fmt::format("{} law, {} tetrahedra, {} volume{}, {} contact{}, {} boundary", fem::to_string(solver.law),
                     fem::to_string(solver.order), fem::to_string(solver.volumetric),
                     insertion::uses_nodal_average(c)
                         ? fmt::format(" (nodal average stabilised by {:g} x shear modulus)", solver.volumetric_stabilization)
                         : "",
                     fem::to_string(solver.contact),
                     edge_radius > 0 ? fmt::format(" (needle edges rounded, radius {:g} um)", edge_radius * 1e6) : "",
                     fem::to_string(solver.boundary));
}

nlohmann::json puncture_json(const insertion::IndentationCase& c, const insertion::IndentationResult& result) {
  nlohmann::json json;
  json["puncture_depth_um"] = result.puncture ? nlohmann::json(result.puncture->depth * 1e6) : nlohmann::json(nullptr);
  json["puncture_force_N"] = result.puncture ? nlohmann::json(result.puncture->force) : nlohmann::json(nullptr);
  json["criterion"] = insertion::to_string(result.puncture ? result.puncture->criterion : insertion::PunctureCriterion::None);
  json["critical_pressure_MPa"] = number_or_null(c.puncture.critical_pressure, 1e-6);
  json["toughness_J_per_m2"] = number_or_null(c.puncture.toughness, 1.0);
  const bool averaged = c.puncture.criterion == insertion::PunctureLaw::AveragedPressure;
  json["puncture_law"] = name_of(insertion::kPunctureLawNames, c.puncture.criterion);
  json["material_length_um"] = averaged ? nlohmann::json(c.puncture.material_length * 1e6) : nlohmann::json(nullptr);
  return json;
}

namespace {
// The ch. 4 bending check of the last step's lateral load (null: no parametric needle, material with an allowable
// stress, or step).
nlohmann::json bending_json(const insertion::IndentationResult& result) {
  if (!result.bending) return nullptr;
  const insertion::BendingCheck& b = *result.bending;
  return {{"lateral_load_N", b.lateral_load},
          {"critical_bending_load_N", b.critical_load},
          {"margin", std::isfinite(b.margin) ? nlohmann::json(b.margin) : nlohmann::json(nullptr)}};
}

}  // namespace

nlohmann::json indentation_inputs_json(const insertion::IndentationCase& c) {
  nlohmann::json inputs = nlohmann::json::object();
  add_parameters_json(insertion::kLoadingParameters, static_cast<const insertion::Loading&>(c), inputs);
  add_parameters_json(fem::kSolverParameters, c.solver, inputs);
  add_parameters_json(mesh::kLayeredBlockParameters, c.block, inputs);
  add_parameters_json(insertion::kPunctureParameters, c.puncture, inputs);
  return inputs;
}

nlohmann::json indentation_json(const insertion::IndentationCase& c, const insertion::IndentationResult& result) {
  nlohmann::json json;
  json["name"] = c.name;
  json["status"] = insertion::to_string(result.status);
  json["reason"] = result.reason;
  json.update(puncture_json(c, result));
  std::vector<double> depth, force, pressure, averaged, energy, work, lateral_x, lateral_y, moment;
  std::vector<int> iterations;
  std::vector<double> volume_ratio, embedded;
  for (const insertion::IndentationStep& s : result.steps) {
    volume_ratio.push_back(s.min_volume_ratio);
    embedded.push_back(s.tip_embedded_depth * 1e6);
    depth.push_back(s.depth * 1e6);
    force.push_back(s.force);
    lateral_x.push_back(s.lateral_force.x());
    lateral_y.push_back(s.lateral_force.y());
    moment.push_back(s.moment.norm());
    pressure.push_back(s.contact_pressure * 1e-6);
    averaged.push_back(s.averaged_pressure * 1e-6);
    energy.push_back(s.strain_energy);
    work.push_back(s.external_work);
    iterations.push_back(s.newton_iterations);
  }
  json["depth_um"] = depth;
  json["force_N"] = force;  // along the needle's axis
  json["lateral_force_x_N"] = lateral_x;
  json["lateral_force_y_N"] = lateral_y;
  json["moment_Nm"] = moment;  // about the needle's base
  json["angle_deg"] = c.angle * 180 / M_PI;
  json["azimuth_deg"] = c.azimuth * 180 / M_PI;
  json["bending"] = bending_json(result);
  json["contact_pressure_MPa"] = pressure;
  if (c.puncture.criterion == insertion::PunctureLaw::AveragedPressure) json["averaged_pressure_MPa"] = averaged;
  json["strain_energy_J"] = energy;
  json["external_work_J"] = work;
  json["newton_iterations"] = iterations;
  json["min_volume_ratio"] = volume_ratio;  // the most compressed tetrahedron's J = det F
  json["tip_embedded_um"] = embedded;       // how far the needles' tips lie inside the tissue (surface contact)
  json["elements"] = result.elements;
  json["nodes"] = result.nodes;
  json["dofs"] = result.dofs;
  json["backend"] = name_of(fem::kSolverBackendNames, c.solver.backend);
  // The built-in backend's strategy; none runs under PETSc (CG with GAMG, docs/fem_solver.md).
  json["linear_solver"] = c.solver.backend == fem::SolverBackend::Petsc
                              ? nlohmann::json(nullptr)
                              : nlohmann::json(name_of(fem::kLinearSolverNames, result.linear_solver));
  json["law"] = name_of(fem::kMaterialLawNames, c.solver.law);
  json["element"] = name_of(fem::kElementOrderNames, c.solver.order);
  json["contact"] = name_of(fem::kContactModelNames, c.solver.contact);
  json["boundary"] = name_of(fem::kBoundaryConditionNames, c.solver.boundary);
  json["volumetric"] = name_of(fem::kVolumetricFormulationNames, c.solver.volumetric);
  json["nodal_average_elements"] = result.nodal_average_elements;
  json["volumetric_stabilization_per_shear_modulus"] = c.solver.volumetric_stabilization;
  json["edge_radius_um"] = insertion::effective_edge_radius(c) * 1e6;
  json["needles"] = needles_json(c, result);
  if (c.array) json["array"] = array_json(c, result);
  nlohmann::json layers = nlohmann::json::array();
  for (const mesh::TissueLayer& layer : c.block.layers) {
    layers.push_back({{"name", layer.name}, {"thickness_um", layer.thickness * 1e6},
                      {"youngs_modulus_MPa", layer.youngs_modulus * 1e-6}, {"poisson_ratio", layer.poisson_ratio}});
  }
  json["layers"] = layers;
  nlohmann::json quality = nlohmann::json::array();
  for (const mesh::LayerQuality& q : result.quality) {
    quality.push_back({{"layer", q.name}, {"tets", q.tets}, {"min_quality", q.min_quality},
                       {"mean_quality", q.mean_quality}});
  }
  json["mesh_quality"] = quality;
  json["remeshes"] = remeshes_json(result);  // [solver] rezone
  std::vector<std::string> notes = indentation_scale_warnings(c);
  for (std::string& note : indentation_result_notes(c, result)) notes.push_back(std::move(note));
  json["notes"] = notes;
  json["inputs"] = indentation_inputs_json(c);
  json["mesh_seconds"] = result.mesh_seconds;
  json["setup_seconds"] = result.setup_seconds;
  json["total_seconds"] = result.total_seconds;
  return json;
}

IndentationWriter::IndentationWriter(std::filesystem::path directory, const insertion::IndentationCase& c)
    : directory_(std::move(directory)), case_(c) {
  create_output_directory(directory_);
}

void IndentationWriter::write_view(const ViewerSources& sources, ViewOptions options) {
  viewer_files_ = viewer_files(sources);
  view_.emplace(case_, options);
}

void IndentationWriter::set_mesh(const mesh::TetMesh& tissue) {
  if (view_) view_->set_mesh(tissue);
  tissue_ = tissue;
  partial_.elements = static_cast<int>(tissue.tets.size());
}

void IndentationWriter::remember(const std::filesystem::path& path) {
  if (std::find(files_.begin(), files_.end(), path) == files_.end()) files_.push_back(path);
}

void IndentationWriter::write_step(const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
  const int k = static_cast<int>(tissue_series_.size()) + 1;
  const std::string tissue_name = fmt::format("{}_step_{:03d}.vtu", case_.name, k);
  const std::string needle_name = fmt::format("{}_needles_step_{:03d}.vtu", case_.name, k);
  write_vtu(indentation_grid(solver, tissue_), directory_ / tissue_name);
  write_vtu(needle_grid(case_, solver.indenter_displacement()), directory_ / needle_name);
  tissue_series_.push_back({step.depth * 1e6, tissue_name});
  needle_series_.push_back({step.depth * 1e6, needle_name});
  write_pvd(tissue_series_, directory_ / (case_.name + ".pvd"));
  write_pvd(needle_series_, directory_ / (case_.name + "_needles.pvd"));
  for (const std::string& name : {tissue_name, needle_name, case_.name + ".pvd", case_.name + "_needles.pvd"}) {
    remember(directory_ / name);
  }
  if (view_) {
    view_->add_step(step, solver);
    StagedFiles files;
    const std::string script = case_.name + "_view.js";
    files.write(directory_ / script, view_script(view_->json()));
    if (view_->steps() == 1) {
      stage_view_page(files, directory_, case_.name + "_view.html", case_.name + ": 3D view", {script},
                      viewer_files_);
    }
    for (const std::filesystem::path& path : files.commit()) remember(path);
  }
  // The curves and the result so far, so that an interrupted run keeps them too.
  partial_.steps.push_back(step);
  write_curves(partial_);
  write_partial_result();
}

void IndentationWriter::add_remesh(const insertion::Remesh& remesh) {
  partial_.remeshes.push_back(remesh);
  write_partial_result();
}

// The result so far, which says it is incomplete until finish() replaces it.
void IndentationWriter::write_partial_result() {
  nlohmann::json json = indentation_json(case_, partial_);
  json["status"] = "incomplete";
  json["reason"] = fmt::format("the run had completed {} of {} load steps when this was written; it stopped there "
                               "(interrupted or killed) or is still running",
                               partial_.steps.size(), case_.steps);
  write_result(json);
}

void IndentationWriter::write_result(const nlohmann::json& json) {
  const std::filesystem::path path = directory_ / (case_.name + "_result.json");
  write_text_file_atomically(path, io::json_text(json));
  remember(path);
}

void IndentationWriter::write_curves(const insertion::IndentationResult& result) {
  for (const auto& [suffix, content] : {std::pair{std::string("_force_depth.csv"), force_depth_csv(result)},
                                        std::pair{std::string("_solver_steps.csv"), solver_statistics_csv(result)}}) {
    const std::filesystem::path path = directory_ / (case_.name + suffix);
    write_text_file_atomically(path, content);
    remember(path);
  }
}

void IndentationWriter::finish(const insertion::IndentationResult& result) {
  const auto write = [&](const std::string& suffix, const std::string& content) {
    const std::filesystem::path path = directory_ / (case_.name + suffix);
    write_text_file_atomically(path, content);
    remember(path);
  };
  write_curves(result);
  if (view_ && view_->steps() > 0 && !result.needles.empty()) {  // the view again, with each needle's puncture state
    view_->set_outcomes(result.needles);
    write("_view.js", view_script(view_->json()));
  }
  write("_puncture.json", io::json_text(puncture_json(case_, result)));
  if (!result.needles.empty()) {
    write("_needles.csv", needles_csv(case_, result));
    const std::filesystem::path map = directory_ / (case_.name + "_needle_map.vtu");
    write_vtu(needle_map_grid(result), map);
    remember(map);
  }
  write_result(indentation_json(case_, result));
}

}  // namespace needlekit::io
