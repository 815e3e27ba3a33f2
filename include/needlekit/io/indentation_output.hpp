// Outputs of an indentation run: the ParaView grid of one step, the force-depth curve and the per-step solver
// statistics as CSV (units in the headers), and the result and puncture point as JSON (units in the keys).
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/indentation_view.hpp"
#include "needlekit/io/view_page.hpp"
#include "needlekit/io/vtu_writer.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::io {

// The tissue in the solver's current state, on the reference nodes (ParaView: Warp By Vector with displacement_m).
// Point fields: displacement_m (3), contact_flag (0, or 1 + needle index), contact_pressure_Pa. Cell fields:
// cauchy_stress_Pa (9), von_mises_stress_Pa, strain_energy_density_J_per_m3, layer_id, youngs_modulus_Pa,
// poisson_ratio. Cells are linear or quadratic tetrahedra as the solver's elements.
VtuGrid indentation_grid(const fem::QuasiStaticSolver& solver, const mesh::TetMesh& tissue);

// The needles' surfaces at the solver's current displacement, as triangles (for display next to the tissue).
VtuGrid needle_grid(const insertion::IndentationCase& indentation_case, double indenter_displacement);

// depth_um,force_N,contact_area_um2,contact_pressure_MPa,max_contact_pressure_MPa,contact_nodes,strain_energy_J,
// external_work_J — one row per converged step, starting with the undeformed state (0, 0).
std::string force_depth_csv(const insertion::IndentationResult& result);

// step,depth_um,newton_iterations,cutbacks,factorizations,cg_iterations,first_residual_N,final_residual_N,
// min_volume_ratio,assembly_s,solve_s,step_s.
std::string solver_statistics_csv(const insertion::IndentationResult& result);

// {"puncture_depth_um", "puncture_force_N" (null if none), "criterion" (the one that fired: "critical-pressure" |
//  "fracture-energy" | "averaged-pressure" | "none"), "puncture_law" ([puncture] criterion: "dissertation" |
//  "averaged-pressure"), "critical_pressure_MPa", "toughness_J_per_m2" (null when not used), "material_length_um"
//  (null unless averaged-pressure)}.
// The models of an FE run, named as in case files: {"law", "element", "contact", "boundary", "volumetric",
// "edge_radius_um" (0: sharp edges: tip-nodes contact or a needle given as a mesh)}; and one line of text.
nlohmann::json fe_models_json(const insertion::IndentationCase& indentation_case);
std::string fe_models_text(const insertion::IndentationCase& indentation_case);

nlohmann::json puncture_json(const insertion::IndentationCase& indentation_case,
                             const insertion::IndentationResult& result);

// The inputs as the parameter tables declare them, under the case file's tables (io/parameter_json.hpp): loading,
// model, solver, mesh and puncture, e.g. {"loading": {"depth_m": 0.00015, ...}, "puncture": {"critical_pressure_Pa":
// null, ...}}. What indentation_json writes under "inputs".
nlohmann::json indentation_inputs_json(const insertion::IndentationCase& indentation_case);

// What the result says of its meshes: one note per rezoning (remesh_note), then deformation_notes.
std::vector<std::string> indentation_result_notes(const insertion::IndentationCase& indentation_case,
                                                  const insertion::IndentationResult& result);
// What the steps say of the deformed mesh: a note when a needle's tip lay inside the tissue by more than the mesh's
// size at the tip (IndentationStep::tip_embedded_depth), naming the first such depth and the deepest, and a note when
// a step crushed a tetrahedron below insertion::kCrushedVolumeRatio of its volume, naming the first such depth and
// the smallest ratio.
std::vector<std::string> deformation_notes(const insertion::IndentationCase& indentation_case,
                                           const insertion::IndentationResult& result);
// The note of one rezoning, as indentation_result_notes gives it: where, why, and what it changed (or why it failed).
std::string remesh_note(const insertion::Remesh& remesh);

// Everything: "name", "status", "reason", the puncture_json keys, "depth_um", "force_N", "contact_pressure_MPa",
// "averaged_pressure_MPa" (p̄_l per step, with the averaged-pressure law),
// "strain_energy_J", "external_work_J", "newton_iterations", "min_volume_ratio", "tip_embedded_um" (arrays, one
// entry per converged step), "elements", "nodes", "dofs", "law", "element", "contact", "boundary", "needles" (io/array_output.hpp:
// needles_json), "array" (with an array: array_json), "layers", "mesh_quality", "remeshes" (one object per
// rezoning: step, depth_um, reason, failure, elements and force_N before and after, force_jump_percent,
// min_volume_ratio before and after, seconds), "notes" (warnings:
// io/scale_warnings.hpp, then indentation_result_notes), "mesh_seconds", "setup_seconds", "total_seconds".
nlohmann::json indentation_json(const insertion::IndentationCase& indentation_case,
                                const insertion::IndentationResult& result);

// Writes DIR/NAME.pvd, DIR/NAME_step_KKK.vtu (tissue), DIR/NAME_needles_step_KKK.vtu, NAME_force_depth.csv and
// NAME_solver_steps.csv after each step, so that a run that stops keeps every completed step, with NAME_result.json
// of the steps so far and "status": "incomplete" (a run that was interrupted or killed leaves it so); finish()
// rewrites the CSV files and the view (with each needle's puncture state and depth) and writes NAME_puncture.json,
// the per-needle NAME_needles.csv and NAME_needle_map.vtu (io/array_output.hpp) and the final NAME_result.json. Every
// file is written to a temporary name and renamed. The constructor creates the directory (IoError naming it when it cannot be written).
class IndentationWriter {
public:
  IndentationWriter(std::filesystem::path directory, const insertion::IndentationCase& indentation_case);
  // Also writes the 3D view (docs/views.md) after each step: NAME_view.js (io/indentation_view.hpp) and, with the
  // first step, NAME_view.html and the viewer folder (io/view_page.hpp). Call before set_mesh; reads the viewer's
  // files at once (IoError when one is missing, before the run).
  void write_view(const ViewerSources& sources, ViewOptions options = {});
  void set_mesh(const mesh::TetMesh& tissue);
  void write_step(const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver);
  // A rezoning (IndentationOptions::on_remesh): NAME_result.json of the steps so far is written again with it.
  void add_remesh(const insertion::Remesh& remesh);
  void finish(const insertion::IndentationResult& result);
  // Every file written so far.
  const std::vector<std::filesystem::path>& files() const { return files_; }
  // Counts a file the caller wrote beside the outputs (the array's needle-map PNG) among files().
  void remember(const std::filesystem::path& path);

private:
  std::filesystem::path directory_;
  const insertion::IndentationCase& case_;
  mesh::TetMesh tissue_;
  std::vector<PvdEntry> tissue_series_;
  std::vector<PvdEntry> needle_series_;
  std::vector<std::filesystem::path> files_;
  insertion::IndentationResult partial_;  // the steps written so far
  std::optional<IndentationView> view_;
  ViewerFiles viewer_files_;
  void write_curves(const insertion::IndentationResult& result);
  void write_partial_result();
  void write_result(const nlohmann::json& json);
};

}  // namespace needlekit::io
