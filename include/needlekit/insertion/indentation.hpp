// Pre-puncture indentation of a layered tissue block by one or several rigid needles (dissertation §3.4-3.5, §6.2):
// mesh the block (refined at each insertion site), place the needles with their tips just above the surface, push
// them down in load steps with the nonlinear quasi-static FE solver, evaluate the puncture criteria after every
// converged step and stop at puncture (or go on to the final depth).
//
// Frames. A needle's surface mesh is given in the needle frame of needle_geometry.hpp (axis z, base at z = 0, tip
// at the largest z, pointing +z). It is turned tip-down by the half-turn about the x axis, (x, y, z) -> (x, −y,
// z_tip − z), and translated so that the centre of its tip (the axis of a cylinder or cone, the centre of a bevel's tip
// face) is over (site.x, site.y) at z = tip_height in the tissue frame of tet_mesh.hpp (top surface z = 0, tissue
// below, needles moving in −z). The block is refined around each site, i.e. under each tip. Depth = needle displacement − the smallest tip height.
//
// Angled insertion (IndentationCase::angle, azimuth; docs/indentation.md "Angled insertion"). The needle placed
// tip-down as above (a bevel's face normal then towards +x) is turned about the vertical through its tip's centre by
// the azimuth φ, then tilted about the horizontal line through that centre perpendicular to the azimuth, so that its
// axis, pointing to the tip, is a = (sin θ cos φ, sin θ sin φ, −cos θ): the tip moves towards the azimuth as it goes
// down. Then it is lifted or lowered so that its lowest point (a rim corner of a tilted flat tip) is at tip_height.
// It moves along a; the depth is its travel along a beyond first touching the undeformed surface (the tip's vertical
// depth is depth · cos θ). At θ = 0 every quantity is the vertical one above, bit for bit.
//
// Stable API (used by the post-puncture model and the `insert` command): IndentationCase, IndentationOptions,
// IndentationResult, run_indentation, pre_puncture_curve.
#pragma once
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/insertion/force_curve.hpp"
#include "needlekit/insertion/needle_array.hpp"
#include "needlekit/insertion/puncture_criteria.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/needle/needle_geometry.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

namespace needlekit::insertion {

// Where one needle of the case starts.
struct NeedleSite {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // m, (x, y) of the tip's centre over the top surface
  double tip_height = 0;  // m, >= 0: height of the tip above the undeformed surface at the start (0: touching)
};

// How the needles move: a case file's [loading]. Its fields are IndentationCase's own (c.depth, c.steps), declared in
// this base so that its parameter table (insertion/loading_parameters.hpp) can be checked field by field.
struct Loading {
  double depth = 200e-6;                     // m, > 0: final depth of the tip below the undeformed surface (along
                                             // the needle's axis when it is tilted)
  // rad, [0, π/2): the needle's axis from the skin's normal (surface contact only; above kSteepAngle a note).
  double angle = 0;
  // rad: the direction of the tilt in the block's x–y plane, from +x (the way the tip travels sideways); the needle is
  // turned about its axis with it, a bevel's face normal towards the azimuth.
  double azimuth = 0;
  int steps = 20;                            // >= 1: equal load steps from 0 to `depth`
  bool stop_at_puncture = true;              // false: continue to `depth` after the puncture point
};

struct IndentationCase : Loading {
  std::string name = "indentation";          // for messages and output file names
  geometry::TriangleMesh needle;             // m, closed and outward-oriented, in the needle frame (tip at max z)
  std::optional<needle::NeedleGeometry> geometry;  // the parametric needle the mesh was built from, if any
  needle::NeedleMeshOptions needle_mesh;     // the segments `needle` was built with (the rounded core's too)
  // m, surface contact on a parametric needle: its edges rounded with this radius (needle/rounded_edges.hpp; unset:
  // needle::default_edge_radius). An error with tip-nodes contact (a flat face) or a needle given as a mesh.
  std::optional<double> edge_radius;
  std::vector<NeedleSite> needles{NeedleSite{}};   // at least one; all move by the same displacement
  // A needle array: `needles` then holds its whole array (array_positions) and `block` the whole block; with a
  // symmetry the reduced model is solved (modelled_case) and every result is the whole array's. Puncture is then
  // evaluated per needle: the run's puncture is the first needle's, and stop_at_puncture stops once every needle has
  // punctured.
  std::optional<NeedleArray> array;
  mesh::LayeredBlockOptions block;           // the tissue block (insertion_sites are taken from `needles`)
  std::optional<mesh::TetMesh> tissue_mesh;  // when set, used as is instead of meshing `block`
  // The needle's material, for the bending check of the lateral load (analysis/bending.hpp); unset: no check.
  std::optional<materials::NeedleMaterial> material;
  fem::SolverOptions solver;                 // law, element order, contact model, boundary, tolerances
  PunctureOptions puncture;                  // criteria evaluated after each step (none: never punctures)
};

// rad: angles steeper than this from the normal get a note (the dissertation's §5.2 designs angled insertion up to 45°).
inline constexpr double kSteepAngle = 0.25 * 3.14159265358979323846;

// The needle's axis, pointing to its tip (the direction it moves in): (sin θ cos φ, sin θ sin φ, −cos θ).
Eigen::Vector3d needle_axis(const IndentationCase& indentation_case);

// Throws InvalidInput naming the case file's key: no needle or an empty needle mesh, a tip height < 0 (the needle
// would start inside the tissue), a site outside the block, depth <= 0 or through the block's height, mesh sizes
// that are not positive or size_far < size_at_tip, steps < 1, invalid puncture parameters.
void validate(const IndentationCase& indentation_case);

// m: the tissue mesh's z extent, or the sum of the block's layer thicknesses (0 when the block has no layers yet:
// the mesher's default).
double tissue_height(const IndentationCase& indentation_case);

// m: the edge radius the contact uses: 0 for tip-nodes contact or a needle given as a mesh, else edge_radius or its
// default.
double effective_edge_radius(const IndentationCase& indentation_case);

// m: the needle's base diameter (the parametric needle's, else the needle mesh's largest extent across its axis).
double base_diameter(const IndentationCase& indentation_case);
// m: the needle's length (the parametric needle's, else the needle mesh's extent along its axis).
double needle_length(const IndentationCase& indentation_case);

// m: how far the needle, turned by the azimuth, is from being its own mirror image across the plane through its axis
// normal to `axis` (0: the plane x = 0 of a quarter model, 1: y = 0 of a half or quarter model), measured by the area
// centroid of its surface off that plane (0 within kMirrorCentroidTolerance of the base diameter). A necessary
// condition: a cone's and a cylinder's centroid is on every such plane, a bevel's lies off its axis on the side away
// from its face (the §6.2 sharp bevel's 35.1 um along its azimuth). A reduced array model mirrors the needles across
// its planes, so where this is not 0 it models a patch whose needles beyond the plane are mirror images.
double off_mirror_plane(const IndentationCase& indentation_case, int axis);
inline constexpr double kMirrorCentroidTolerance = 1e-3;

// Makes the case an array case: `array`, every needle of it at `tip_height` (array_positions), and the block's
// width and length (when `size_width`/`size_length`) the array's footprint plus its margin on every side.
void set_array(IndentationCase& indentation_case, const NeedleArray& array, double tip_height, bool size_width = true,
               bool size_length = true);

// The case that is meshed and solved: the case itself, or for an array with a symmetry its reduced model (the half
// or quarter block, the needles in it, some cut by the symmetry planes, and the symmetry boundary condition).
IndentationCase modelled_case(const IndentationCase& indentation_case);

// Whether the FE averages the volume at the nodes in some layer of the case's tissue (fem::nodal_average_applies).
bool uses_nodal_average(const IndentationCase& indentation_case);

// A block meshed for a run whose solver is "auto" gets a coarse level, and with it the two-grid solver, from this
// estimated tetrahedron count on (mesh::estimated_tetrahedra), with or without the nodal average. With the coarse
// level at three times the sizes the two-grid solver beats Cholesky-CG on every skin block measured, from 17k
// tetrahedra (1.23 s against 1.5-1.7 s) through 29k (1.9-2.0 against 2.9-3.0 s), 43k (3.1 against 4.3 s) and 87k
// (9.8 against 12.0 s; BENCHMARKS.md, eleventh session); with the nodal average, whose alternative is CG on the
// one-ring preconditioner's Cholesky factor, the §6.2 cylinder's 33k tetrahedra took 22.1 s against 30.6 s and the
// blunt bevel's 55k 25.1 s against 54 s (ninth session). At 4.4k tetrahedra both take 0.6 s: small blocks keep
// the direct path, which needs no second mesh.
inline constexpr double kTwoGridMinimumTetrahedra = 25'000;
// Whether the block of the case is meshed with a coarse level (mesh::LayeredBlockOptions::coarse_level): the solver
// asks for "two-grid", or "auto" on a block of kTwoGridMinimumTetrahedra or more, with linear elements. False for a
// case with its own tissue mesh.
bool meshes_coarse_level(const IndentationCase& indentation_case);

// The needles' surfaces placed in the tissue frame at zero displacement (one per site), as the solver takes them
// (with rounded edges, each needle's eroded core and its edge radius).
std::vector<fem::Indenter> placed_indenters(const IndentationCase& indentation_case);

enum class IndentationStatus {
  Punctured,     // a puncture criterion fired (and the run stopped there unless stop_at_puncture is false)
  ReachedDepth,  // the final depth was reached without puncture
  SolverFailed,  // a load step did not converge after all cut-backs; every completed step is kept
};
inline constexpr EnumTable<IndentationStatus, 3> kIndentationStatusNames{{
    {IndentationStatus::Punctured, "punctured", "a puncture criterion fired"},
    {IndentationStatus::ReachedDepth, "reached-depth", "the final depth was reached without puncture"},
    {IndentationStatus::SolverFailed, "solver-failed",
     "a load step did not converge after all cut-backs; completed steps are kept"},
}};
std::string_view to_string(IndentationStatus status);

// Below this volume ratio J = det F a tetrahedron is crushed, and the forces depend on the mesh: under the §6.2 sharp
// bevel (surface contact) the smallest ratio falls below it at 60 um on an 8 um tip mesh and at 40 um on 5.5 um;
// in the 2.40 M-equivalent array it first did at 120 um, where Newton began to slow (BENCHMARKS.md, twentieth
// session).
inline constexpr double kCrushedVolumeRatio = 0.3;

// One converged load step.
struct IndentationStep {
  double depth = 0;                  // m, tip depth below the undeformed surface
  double force = 0;                  // N, total reaction force on the needles (positive pushing down)
  std::vector<double> needle_force;  // N, per needle (of the whole array)
  std::vector<double> needle_contact_area;  // m^2, per needle (of the whole array)
  double contact_area = 0;           // m^2, total tissue area in contact with the needles
  double contact_pressure = 0;       // Pa, mean pressure under the tips: force / contact_area (Eq 3.17's P_s)
  double max_contact_pressure = 0;   // Pa, largest nodal contact pressure
  // Pa, the averaged-pressure law's p̄_l (averaged_contact_pressure.hpp), the highest of the needles' and per needle
  // (of the whole array); 0 and empty unless [puncture] criterion = "averaged-pressure"
  double averaged_pressure = 0;
  std::vector<double> needle_averaged_pressure;
  int contact_nodes = 0;             // nodes in contact, all needles (of the model solved: a reduced array's)
  double strain_energy = 0;          // J, stored in the tissue (Δ = ½uᵀKu of Eq 3.17)
  // N, the tissue's force on the needles across their axis (its component along the axis is `force`), block axes.
  Eigen::Vector3d lateral_force = Eigen::Vector3d::Zero();
  // N m, the moment of the tissue's forces on the needles about each needle's base centre (on its axis), block axes.
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double external_work = 0;          // J, work of the needles since the start (trapezoidal over the steps)
  int newton_iterations = 0;         // of this step (all substeps)
  int cutbacks = 0;                  // step halvings needed
  int factorizations = 0;            // fresh Cholesky factorizations of this step
  int linear_iterations = 0;         // CG iterations on a reused factorization, summed over the step's solves
  double min_volume_ratio = 1;       // the most compressed tetrahedron's J = det F (fem::StepResult's)
  double tip_embedded_depth = 0;     // m, how far the needles' tips lie inside the tissue (fem::StepResult's)
  double max_residual = 0;           // N, residual norm at the first Newton iteration of the step
  double final_residual = 0;         // N, residual norm at the last Newton iteration of the step
  double assembly_seconds = 0;       // wall time of this step
  double solve_seconds = 0;
  double step_seconds = 0;
};

struct IndentationProgress {
  std::string stage;     // "mesh", "setup", "step"
  int step = 0;          // steps completed so far
  int steps = 0;         // steps planned
  double depth = 0;      // m, depth of the last converged step
  double fraction = 0;   // [0, 1], of the planned steps (or up to the puncture point)
};

// The displacement field of one converged step (m, one vector per FE node), for warm starts.
struct StepDisplacement {
  double depth = 0;  // m
  std::vector<Eigen::Vector3d> displacement;
};

struct Remesh;

struct IndentationOptions {
  // Called on the calling thread at each stage and after each converged step.
  std::function<void(const IndentationProgress&)> progress;
  // Called after each converged step with the solver in that state (e.g. to write a .vtu of the step).
  std::function<void(const IndentationStep&, const fem::QuasiStaticSolver&)> on_step;
  // Called after meshing with the tissue mesh that is solved (e.g. for its layer ids in output files), and again with
  // each rezoned mesh (SolverOptions::rezone) before the steps solved on it. A rezoned mesh has the earlier mesh's
  // boundary: its boundary nodes are the earlier mesh's, at the same reference positions and in the same order
  // (mesh/rezoned_mesh.hpp).
  std::function<void(const mesh::TetMesh&)> on_mesh;
  // Called when a rezoning has been tried (SolverOptions::rezone), with its record as it will stand in
  // IndentationResult::remeshes, whether it worked or not (e.g. to report it while the run goes on).
  std::function<void(const Remesh&)> on_remesh;
  // Warm start: the step displacements of an earlier run of the same case on the same mesh (its
  // IndentationResult::displacements), e.g. at slightly different material parameters. A load step at a depth found
  // there starts Newton from that field (QuasiStaticSolver::advance_to(depth, start)); other steps run as usual.
  const std::vector<StepDisplacement>* warm_start = nullptr;
  // Keep every converged load step's displacement field in IndentationResult::displacements.
  bool keep_displacements = false;
};

// One needle of the case (of the whole array), per converged step. Its puncture is evaluated by the case's
// criteria on its own force and contact area and its share of the stored energy (in proportion to its work).
struct NeedleOutcome {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // m, (x, y) of the tip's centre
  std::vector<double> force;             // N, per step
  std::vector<double> depth;             // m, per step: the tip below the undeformed surface
  std::optional<PuncturePoint> puncture;  // its own puncture point (force: this needle's), if any
  int puncture_step = 0;                 // the step (from 1) in which it punctured; 0: not punctured
  // m, >= 0: the travel of the punctured needle beyond its puncture depth at the last step (the part of it that
  // the model takes as inserted: the tissue's deflection at puncture is not recovered); 0 when not punctured
  double inserted_depth = 0;
};

// The totals of a needle array (Larrañeta et al. 2014's penetrated fraction: inserted depth / needle length).
struct ArrayOutcome {
  std::vector<double> plate_travel;        // m, per step: the common displacement of the needles (and the plate)
  std::vector<double> punctured_fraction;  // [0, 1], per step: needles punctured so far
  std::optional<double> first_puncture_travel;  // m, the plate's travel when the first needle punctured
  double mean_inserted_depth = 0;          // m, over every needle (0 for the unpunctured), last step
  double inserted_depth_spread = 0;        // m, the standard deviation of the same
  double mean_penetrated_fraction = 0;     // [0, 1], mean_inserted_depth / the needle's length
};

// The ch. 4 bending check (dissertation §5.2, Eqs 5.7/5.8) on the FE's lateral load at the last step: the needle
// as a cantilever loaded across its axis at the tip.
struct BendingCheck {
  double lateral_load = 0;          // N, |lateral_force| at the last converged step
  double critical_load = 0;         // N, analysis::critical_bending_load with the material's allowable stress
  double margin = 0;                // critical_load / lateral_load (infinite for no lateral load); >= 1: safe
};

// One rezoning of the tissue (fem::SolverOptions::rezone; mesh/rezoned_mesh.hpp): where, why, and what it changed.
// The step at `depth` was solved on the old mesh; the new mesh is brought into equilibrium at the same depth before
// the run goes on.
struct Remesh {
  int step = 0;                        // the load step after which it happened (the last one kept)
  double depth = 0;                    // m
  std::string reason;                  // the smallest J below rezone_volume_ratio, or the next step's failure
  int elements_before = 0, elements_after = 0;
  double force_before = 0, force_after = 0;                     // N, at `depth` on the old and on the new mesh
  double min_volume_ratio_before = 0, min_volume_ratio_after = 0;  // J = det F
  double seconds = 0;                  // meshing, transfer and the new mesh's equilibrium
  // How the new mesh came to equilibrium from the transferred state (fem::kStartBalanceNames), when it did.
  fem::StartBalance balance = fem::StartBalance::NoStart;
  std::string failure;                 // not empty: the rezoning failed (why), and the run went on without it
  double force_jump() const { return force_before != 0 ? force_after / force_before - 1 : 0; }
};

struct IndentationResult {
  IndentationStatus status = IndentationStatus::ReachedDepth;
  std::string reason;                         // why the run stopped (always set)
  std::vector<IndentationStep> steps;         // every converged step, in order
  std::optional<PuncturePoint> puncture;      // empty: no criterion fired within the simulated depth
  std::vector<NeedleOutcome> needles;         // one per needle of the case (of the whole array)
  std::optional<ArrayOutcome> array;          // with IndentationCase::array
  // With a parametric needle whose material has an allowable stress, after at least one step.
  std::optional<BendingCheck> bending;
  std::vector<StepDisplacement> displacements;  // per converged load step, with IndentationOptions::keep_displacements
  int warm_started_steps = 0;                 // load steps that started from IndentationOptions::warm_start
  std::vector<Remesh> remeshes;               // with SolverOptions::rezone, in order
  int elements = 0;                           // tetrahedra of the tissue mesh
  int nodes = 0;                              // FE nodes (with the mid-edge nodes of quadratic elements)
  int dofs = 0;                               // free degrees of freedom
  fem::LinearSolver linear_solver = fem::LinearSolver::CholeskyCg;  // the one the FE solver used
  int nodal_average_elements = 0;  // linear tetrahedra with the nodal-averaged volume (what `volumetric` resolved to)
  std::vector<mesh::LayerQuality> quality;    // per layer, when the block was meshed here
  double mesh_seconds = 0;                    // wall time of meshing
  double setup_seconds = 0;                   // building the solver (symbolic factorization, ...)
  double total_seconds = 0;
};

// Runs the case. Throws InvalidInput for an invalid case (see validate) or mesh; numerical failure is a status.
IndentationResult run_indentation(const IndentationCase& indentation_case, const IndentationOptions& options = {});

// The force-depth curve of the converged steps, starting at (0, 0), and the puncture point, for the post-puncture
// model.
PrePunctureCurve pre_puncture_curve(const IndentationResult& result);

}  // namespace needlekit::insertion
