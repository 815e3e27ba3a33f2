// The quasi-static solver's options, their enums and names, the rigid needle it is given, and its per-iteration
// records: what the solver's parts (function space, boundary conditions, contact, tangent and linear solves) read,
// without the solver itself (quasi_static_solver.hpp includes this header). Meanings in quasi_static_solver.hpp and
// docs/fem_solver.md. SI units throughout.
#pragma once
#include <Eigen/Core>
#include <functional>
#include <string>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/fem/hyperelastic_law.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::fem {

enum class ElementOrder {
  Linear,     // 4-node tetrahedra (the dissertation's); lock for nu -> 0.5
  Quadratic,  // 10-node tetrahedra (mid-edge nodes added), 4-point Gauss rule: the locking-free option
};
enum class ContactModel { TipNodes, Surface };
enum class LinearSolver {
  Automatic,   // TwoGrid for quadratic elements, and for linear ones given a coarse level (a split mesh's parent, or
               // the body meshed again at coarser sizes: insertion::run_indentation meshes one for large blocks);
               // else CholeskyCg
  Cholesky,    // a fresh CHOLMOD factorization per Newton iteration
  CholeskyCg,  // conjugate gradients preconditioned by the last factorization, while cheaper than a new one
  TwoGrid,     // conjugate gradients preconditioned by a two-grid cycle (Chebyshev smoothing, CHOLMOD on the coarse
               // level): memory and time per iteration linear in the mesh size. Linear elements need a coarse level;
               // quadratic ones use their corner nodes as the coarse level
};
// Where the linear solves run (docs/fem_solver.md, "PETSc backend").
enum class SolverBackend {
  Builtin,  // this library's solves (LinearSolver), one process with threads
  Petsc,    // PETSc's CG with algebraic multigrid (GAMG) across MPI ranks; only in a build with NEEDLEKIT_WITH_PETSC
};
// How the volumetric part of the neo-Hookean law is integrated on linear tetrahedra.
enum class VolumetricFormulation {
  Automatic,     // NodalAverage for linear tetrahedra of layers with poisson_ratio >= kNearlyIncompressible under the
                 // neo-Hookean law; Element otherwise
  Element,       // per element, as every other term (linear tetrahedra lock as nu -> 0.5)
  NodalAverage,  // λ/2 (ln J)^2 on the nodal-averaged volume ratio (Bonet & Burton 1998; FEBio's UT4 without its
                 // isochoric stabilisation): locking-free linear tetrahedra. Linear elements and neo-Hookean only
};
// Poisson's ratio from which VolumetricFormulation::Automatic averages the volume at the nodes.
inline constexpr double kNearlyIncompressible = 0.45;

enum class BoundaryCondition {
  SidesAndBottomFixed,    // §3.4: every node on the four sides and the bottom is fixed; top free
  BottomFixed,            // bottom fixed, sides free
  BottomFixedSidesRoller, // bottom fixed, sides slide (normal displacement zero)
  SymmetryPlanes,         // u_x = 0 on x = min, u_y = 0 on y = min, u_z = 0 on the bottom; other faces free
                          // (homogeneous uniaxial tests)
  QuarterSymmetry,        // u_x = 0 on x = min, u_y = 0 on y = min (symmetry planes through the needle axis);
                          // x = max, y = max and the bottom fixed: a quarter of a centred §3.4 block
  HalfSymmetry,           // u_y = 0 on y = min (a symmetry plane through the needles); the other sides and the bottom
                          // fixed: a half of a centred §3.4 block
};

// The names of the enums above, as case files, JSON and the CLI help write them (core/enum_table.hpp).
inline constexpr EnumTable<ElementOrder, 2> kElementOrderNames{{
    {ElementOrder::Linear, "linear", "4-node tetrahedra (the dissertation's; lock as nu -> 0.5)"},
    {ElementOrder::Quadratic, "quadratic", "10-node tetrahedra: free of volumetric locking"},
}};
inline constexpr EnumTable<ContactModel, 2> kContactModelNames{{
    {ContactModel::Surface, "surface", "penalty contact of the tissue's top surface with the needle's surface mesh"},
    {ContactModel::TipNodes, "tip-nodes", "the dissertation's rule: nodes under a flat tip follow it in z"},
}};
inline constexpr EnumTable<LinearSolver, 4> kLinearSolverNames{{
    {LinearSolver::Automatic, "auto",
     "two-grid for quadratic elements, a split mesh or a large meshed block, else cholesky-cg"},
    {LinearSolver::TwoGrid, "two-grid", "CG with a two-grid preconditioner: memory and time linear in the mesh"},
    {LinearSolver::CholeskyCg, "cholesky-cg", "CG preconditioned by the last CHOLMOD factorization"},
    {LinearSolver::Cholesky, "cholesky", "a fresh CHOLMOD factorization per Newton iteration"},
}};
inline constexpr EnumTable<SolverBackend, 2> kSolverBackendNames{{
    {SolverBackend::Builtin, "builtin", "this library's linear solves (linear_solver), one process"},
    {SolverBackend::Petsc, "petsc", "PETSc's CG + GAMG across MPI ranks (mpirun -np N); -ksp_*/-pc_* options apply"},
}};
inline constexpr EnumTable<BoundaryCondition, 6> kBoundaryConditionNames{{
    {BoundaryCondition::SidesAndBottomFixed, "sides-and-bottom-fixed", "§3.4: the four sides and the bottom fixed"},
    {BoundaryCondition::BottomFixed, "bottom-fixed", "the bottom fixed, the sides free"},
    {BoundaryCondition::BottomFixedSidesRoller, "bottom-fixed-sides-roller", "the bottom fixed, the sides slide"},
    {BoundaryCondition::SymmetryPlanes, "symmetry-planes",
     "u_x = 0 on x = min, u_y = 0 on y = min, u_z = 0 on the bottom (uniaxial tests)"},
    {BoundaryCondition::QuarterSymmetry, "quarter-symmetry",
     "symmetry planes through the needle axis at x = min and y = min, the other sides and the bottom fixed"},
    {BoundaryCondition::HalfSymmetry, "half-symmetry",
     "a symmetry plane through the needles at y = min, the other sides and the bottom fixed"},
}};
inline constexpr EnumTable<VolumetricFormulation, 3> kVolumetricFormulationNames{{
    {VolumetricFormulation::Automatic, "auto",
     "nodal-average for linear neo-Hookean layers with nu >= 0.45, else element"},
    {VolumetricFormulation::Element, "element",
     "per element, as every other term (linear tetrahedra lock as nu -> 0.5)"},
    {VolumetricFormulation::NodalAverage, "nodal-average",
     "the volume ratio averaged at the nodes (Bonet & Burton 1998): locking-free linear tetrahedra"},
}};

std::string_view to_string(ElementOrder order);
std::string_view to_string(ContactModel contact);
std::string_view to_string(LinearSolver solver);
std::string_view to_string(BoundaryCondition condition);
std::string_view to_string(VolumetricFormulation formulation);
std::string_view to_string(SolverBackend backend);
// Parse the names of the tables above; throw InvalidInput naming `what` and the accepted names.
ElementOrder element_order_from_string(const std::string& text, const std::string& what = "order");
ContactModel contact_model_from_string(const std::string& text, const std::string& what = "contact");
BoundaryCondition boundary_condition_from_string(const std::string& text, const std::string& what = "boundary");
VolumetricFormulation volumetric_formulation_from_string(const std::string& text,
                                                         const std::string& what = "volumetric");

// A rigid needle. `surface` is closed and outward-oriented, already placed in the tissue frame at zero indenter
// displacement (its tip on or above the top surface z = 0); the needle translates by d * direction.
struct Indenter {
  geometry::TriangleMesh surface;               // m
  Eigen::Vector3d direction{0.0, 0.0, -1.0};    // unit after normalisation; TipNodes requires (0, 0, -1)
  // m, >= 0, Surface contact only: the rigid body is every point within edge_radius of `surface`, which is then
  // the needle's eroded core (needle/rounded_edges.hpp): the needle with its edges rounded with this radius.
  double edge_radius = 0;
};

// Called after every Newton iteration (from the calling thread).
struct SolverProgress {
  double target_displacement = 0;   // m, the displacement of the current (sub)step
  int iteration = 0;                // Newton iteration within the (sub)step, from 1
  double residual_norm = 0;         // N, free-dof residual
  int cutbacks = 0;                 // so far in this advance_to call
  int augmentation = 0;             // surface contact: augmented-Lagrangian updates so far in this (sub)step
  double step_length = 1;           // the line search's factor on the Newton update
  int linear_iterations = 0;        // CG iterations of the update (0: a direct solve)
  bool contact_set_changed = false;  // surface contact: the nodes in contact differ from the last iteration's
};

struct SolverOptions {
  MaterialLaw law = MaterialLaw::StVenantKirchhoff;   // constitutive law
  ElementOrder order = ElementOrder::Linear;          // element order
  VolumetricFormulation volumetric = VolumetricFormulation::Automatic;  // linear tetrahedra near incompressibility
  double volumetric_stabilization = 1.0;  // >= 0, nodal-averaged volume only: each tetrahedron keeps the bulk term
                                          // min(λ, this × μ) for itself, the nodes carry the rest (0: Bonet &
                                          // Burton's pure nodal average, whose elements can collapse at depth;
                                          // docs/fem_solver.md)
  ContactModel contact = ContactModel::TipNodes;      // needle model
  BoundaryCondition boundary = BoundaryCondition::SidesAndBottomFixed;  // on the mesh's bounding box faces
  double boundary_tolerance = 1e-9;      // m, >= 0: a node is on a box face within this distance (plus 1e-9 of
                                         // the box diagonal)

  // Newton convergence: residual AND (displacement OR energy), checked after each update (du is the last update;
  // with Newton's quadratic convergence the remaining error is far smaller). FEBio's defaults, for comparison, are
  // 1e-3 (displacement) and 1e-2 (energy) with the residual test off.
  double residual_tolerance = 1e-6;      // (0, 1): ||R_free|| <= tol * max(||f_reaction||, ||f_int||, tiny)
  double displacement_tolerance = 1e-5;  // (0, 1): ||du|| <= tol * ||u||
  double energy_tolerance = 1e-8;        // (0, 1): |du . R| <= tol * |du_1 . R_1| (first iteration of the step)
  int max_iterations = 0;                // Newton iterations per (sub)step, >= 0; 0: newton_iteration_limit's
                                         // default for the contact model
  bool line_search = true;               // backtracking (Armijo) on the potential energy, with a tangent shift
                                         // when the factorization is not positive definite
  int max_cutbacks = 8;                  // halvings of a failed step before giving up, >= 0
  bool linear_predictor = true;          // first iterate = linearised elastic solution (§3.4); false: previous u
  bool extrapolate_predictor = true;     // once a step has converged, later steps start from the converged states
                                         // extrapolated to the new step (linearly from two, quadratically from
                                         // three) instead of the linearised solve: one linear solve less per step;
                                         // the first step always follows linear_predictor

  // Surface contact (ContactModel::Surface).
  double penalty_factor = 100.0;         // > 0: penalty stiffness per area = factor * E / h of the adjacent elements
  double penetration_tolerance = 1e-3;   // (0, 1): augmented-Lagrangian updates until max penetration <= tol *
                                         // max(indenter displacement, smallest contact element size)
  int max_augmentations = 6;             // augmented-Lagrangian updates per step, >= 0 (0: pure penalty)
  double friction = 0;                   // >= 0: Coulomb coefficient between needle and tissue, regularised (tangential
                                         // penalty as the normal one; docs/fem_solver.md); 0: frictionless
  bool two_pass = false;                 // also the needle's sharp edges and vertices against the tissue's faces
                                         // (docs/fem_solver.md); off: the tissue's nodes against the needle only

  // Linear solves (LinearSolver). CholeskyCg: CG gets at most (estimated factorization cost / estimated CG
  // iteration cost) iterations on the last factor, from CHOLMOD's flop count and the factor's size (not timed: runs
  // do not depend on the machine's load), capped by max_reuse_iterations, and the factor is renewed at once when
  // the previous CG solve used more than half of that. TwoGrid: CG with the two-grid cycle, whose coarse operator
  // is renewed when a solve needed more than two_grid_refresh_iterations (so is the PETSc backend's preconditioner,
  // src/fem/petsc/petsc_linear_solve.cpp). Both start from the projection of the solution on the last 12 solutions
  // (Krylov recycling). With the nodal-averaged volume, CholeskyCg factorizes a one-ring matrix that bounds the
  // tangent from above, not the two-ring tangent itself, and CG always runs (docs/fem_solver.md); Cholesky
  // factorizes the tangent itself.
  LinearSolver linear_solver = LinearSolver::Automatic;   // the built-in backend's strategy
  SolverBackend backend = SolverBackend::Builtin;         // Petsc: linear_solver is not used
  int two_grid_refresh_iterations = 25;  // >= 1: see above
  int max_reuse_iterations = 40;         // >= 1: cap on the CG iterations of one solve
  double linear_tolerance = 1e-10;       // (0, 1): tightest CG relative residual. Inexact Newton: CG stops at the
                                         // Eisenstat-Walker forcing term (|R_k| / |R_k-1|)^2 (1e-3 in the first
                                         // iteration, at most 0.1), never tighter than a tenth of the residual
                                         // target or this

  int threads = 0;                       // TBB threads for assembly, 0 = default

  // Rezoning (issue 35 item 3), done by insertion::run_indentation between load steps, not by the solver: the
  // deformed tissue is meshed anew (mesh/rezoned_mesh.hpp) and the run continues on the new mesh. Surface contact
  // and linear tetrahedra only.
  bool rezone = false;                   // rezone when a step leaves the tissue crushed or fails
  double rezone_volume_ratio = 0.5;      // (0, 1): rezone after a step whose smallest J = det F fell below this
  int max_remeshes = 10;                 // >= 1: rezonings per run at most
  std::function<void(const SolverProgress&)> progress;  // optional

  // Throws InvalidInput naming the first field outside its range ("solver max_cutbacks = -1: expected >= 0").
  void validate() const;
};

// Newton iterations per (sub)step when SolverOptions::max_iterations is 0: kNewtonIterations, and
// kSurfaceContactNewtonIterations under surface contact, whose contact set changes while tissue wraps a needle's rim
// (the §6.2 cylinder on a 40 um mesh: 596.9 um reached with 25, 831 um with 60, docs/indentation.md).
inline constexpr int kNewtonIterations = 25;
inline constexpr int kSurfaceContactNewtonIterations = 60;
int newton_iteration_limit(const SolverOptions& options);

// Whether the nodal-averaged volume can act under these options at all: the neo-Hookean law on linear tetrahedra,
// volumetric not "element".
bool nodal_average_possible(const SolverOptions& options);
// Whether it treats the tetrahedra of a layer with this Poisson's ratio (volumetric = "nodal-average": every
// layer; "auto": from kNearlyIncompressible on). The solver, the case reader and the models line ask this.
bool nodal_average_applies(const SolverOptions& options, double poisson_ratio);

// One Newton iteration.
struct IterationRecord {
  double residual_norm = 0;      // N, free-dof residual before the update
  double increment_norm = 0;     // m, ||du|| of the update
  double energy_norm = 0;        // J, |du . R|
  double step_length = 1;        // line-search factor
  double assembly_seconds = 0;   // wall time of residual + tangent assembly
  double solve_seconds = 0;      // wall time of factorization + solve
  bool factorized = false;       // a fresh numeric factorization was taken
  bool line_search_failed = false;  // no sufficient decrease found: the full step was taken
  int linear_iterations = 0;     // preconditioned CG iterations (0: direct solve with a fresh factorization)
};

}  // namespace needlekit::fem
