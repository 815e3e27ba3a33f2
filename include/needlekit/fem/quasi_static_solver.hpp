// Nonlinear quasi-static indentation of a tetrahedral tissue block by rigid needles (dissertation §3.4).
//
// Total-Lagrangian tetrahedra (linear, or quadratic T10 built from the linear mesh by adding mid-edge nodes) with
// the Green-Lagrange strain (Eq 3.3 as corrected in the notes), the dissertation's linear stress-strain law
// S = D E (Eqs 3.4/3.5, i.e. St Venant-Kirchhoff) or a compressible neo-Hookean law. The prescribed needle
// displacement is applied in load steps; the first iterate of the first step is the linear elastic solution (§3.4:
// "we apply the solution obtained from the linear finite element as our initial guessed answer"), later steps start
// from the last converged state plus the last increment (or, optionally, the linearised solution about it). Each
// step is solved by Newton's method with a backtracking line search on the total potential energy (the problem is
// conservative; this replaces Matlab's trust-region dogleg of §3.4 and plays the same role); a failed step is cut
// back automatically. Linear systems: CHOLMOD supernodal Cholesky (symbolic analysis once per solver), used
// directly or as the preconditioner of conjugate gradients while a fresh factorization would cost more (inexact
// Newton). Element assembly is threaded (TBB).
//
// The needle is a rigid indenter in one of two models:
//  - ContactModel::TipNodes, the dissertation's rule (§3.4, Eq 3.9-3.12): the top-surface nodes under the needle's
//    flat tip face follow the tip along the indentation direction and are free across it (frictionless); the
//    reaction force is the sum of their internal forces (Eq 3.11). Only a flat tip face defines such nodes; for a
//    sharp tip the single top node nearest to the apex is used.
//  - ContactModel::Surface: frictionless unilateral contact of the tissue's top-surface nodes against the needle's
//    actual (closed) surface mesh, node-to-surface, enforced by a penalty with augmented-Lagrangian updates (the
//    multipliers are updated between Newton solves until the penetration is below a tolerance). Cones and bevels
//    indent with their real shape.
// Several needles may indent at once; they all move by the same displacement along their own directions.
//
// Frame (tet_mesh.hpp): tissue top surface z = 0, tissue z <= 0, needles above moving in -z. SI units throughout.
#pragma once
#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/fem/hyperelastic_law.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/mesh/tet_mesh.hpp"
#include "needlekit/mesh/coarse_level.hpp"

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
inline constexpr EnumTable<BoundaryCondition, 5> kBoundaryConditionNames{{
    {BoundaryCondition::SidesAndBottomFixed, "sides-and-bottom-fixed", "§3.4: the four sides and the bottom fixed"},
    {BoundaryCondition::BottomFixed, "bottom-fixed", "the bottom fixed, the sides free"},
    {BoundaryCondition::BottomFixedSidesRoller, "bottom-fixed-sides-roller", "the bottom fixed, the sides slide"},
    {BoundaryCondition::SymmetryPlanes, "symmetry-planes",
     "u_x = 0 on x = min, u_y = 0 on y = min, u_z = 0 on the bottom (uniaxial tests)"},
    {BoundaryCondition::QuarterSymmetry, "quarter-symmetry",
     "symmetry planes through the needle axis at x = min and y = min, the other sides and the bottom fixed"},
}};
inline constexpr EnumTable<VolumetricFormulation, 3> kVolumetricFormulationNames{{
    {VolumetricFormulation::Automatic, "auto",
     "nodal-average for linear neo-Hookean layers with nu >= 0.45, else element"},
    {VolumetricFormulation::Element, "element",
     "per element, as every other term (linear tetrahedra lock as nu -> 0.5)"},
    {VolumetricFormulation::NodalAverage, "nodal-average",
     "the volume ratio averaged at the nodes (Bonet & Burton 1998): locking-free linear tetrahedra"},
}};

std::string to_string(ElementOrder order);
std::string to_string(ContactModel contact);
std::string to_string(LinearSolver solver);
std::string to_string(BoundaryCondition condition);
std::string to_string(VolumetricFormulation formulation);
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
  // is renewed when a solve needed more than two_grid_refresh_iterations. Both start from the projection of the
  // solution on the last 12 solutions (Krylov recycling). With the nodal-averaged volume, CholeskyCg factorizes a
  // one-ring matrix that bounds the tangent from above, not the two-ring tangent itself, and CG always runs
  // (docs/fem_solver.md); Cholesky factorizes the tangent itself.
  LinearSolver linear_solver = LinearSolver::Automatic;
  int two_grid_refresh_iterations = 25;  // >= 1: see above
  int max_reuse_iterations = 40;         // >= 1: cap on the CG iterations of one solve
  double linear_tolerance = 1e-10;       // (0, 1): tightest CG relative residual. Inexact Newton: CG stops at the
                                         // Eisenstat-Walker forcing term (|R_k| / |R_k-1|)^2 (1e-3 in the first
                                         // iteration, at most 0.1), never tighter than a tenth of the residual
                                         // target or this

  int threads = 0;                       // TBB threads for assembly, 0 = default
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

// How a load step ended. The numerical failures say which part of the solver gave way.
enum class StepStatus {
  Converged,            // the target displacement was reached
  InvertedElement,      // every cut-back still inverted an element (J <= 0 at a quadrature point)
  IterationLimit,       // Newton did not reach the tolerances within max_iterations (or the residual was not finite)
  LinearSolverFailure,  // the tangent system could not be solved (factorization or CG failed, also shifted)
  ContactCycling,       // Newton did not converge while the set of contact nodes kept changing between iterations
  InvalidTarget,        // the target displacement is not finite
};
std::string to_string(StepStatus status);

struct StepResult {
  bool converged = false;                // status == StepStatus::Converged
  StepStatus status = StepStatus::Converged;
  std::string reason;                    // empty when converged; else what failed and at which displacement
  int newton_iterations = 0;             // total over substeps and augmentations
  int cutbacks = 0;
  int substeps = 0;                      // converged substeps taken
  double indenter_displacement = 0;      // m, displacement actually reached (== target when converged)
  std::vector<double> indenter_force;    // N, per needle: reaction on the needle along -direction (>0 pushing)
  std::vector<double> max_contact_pressure;   // Pa, per needle: largest nodal contact pressure
  std::vector<double> mean_contact_pressure;  // Pa, per needle: force / contact area
  std::vector<double> contact_area;           // m^2, per needle: tributary area of the nodes in contact
  std::vector<int> contact_nodes;             // per needle: nodes in contact
  double max_penetration = 0;            // m, Surface contact: largest penetration after the last augmentation
  double strain_energy = 0;              // J, stored in the tissue
  double external_work = 0;              // J, sum over needles of the trapezoidal integral of force over displacement
                                         // since the solver was built
  std::vector<IterationRecord> iterations;  // all Newton iterations of this call
  int factorizations = 0;                // numeric factorizations in this call
  double assembly_seconds = 0;           // totals of this call
  double solve_seconds = 0;
  double total_seconds = 0;
  std::vector<Eigen::Vector3d> contact_force;  // N, per needle: the tissue's resultant force on the needle (Surface:
                                               // normal and friction forces of both passes; TipNodes: -indenter_force
                                               // along the direction)
};

// Per-element outputs (one value per tetrahedron, averaged over its quadrature points) for VTU.
struct ElementFields {
  std::vector<Eigen::Matrix3d> cauchy_stress;   // Pa
  std::vector<double> von_mises_stress;         // Pa
  std::vector<double> strain_energy_density;    // J/m^3 of reference volume
  std::vector<double> volume_ratio;             // J = det F
};

class QuasiStaticSolver {
public:
  // Throws InvalidInput for an invalid mesh (empty, inverted or degenerate tetrahedra, a layer index out of range,
  // E <= 0, nu outside (-1, 0.5)), an indenter whose surface is empty or starts inside the tissue (below z = 0 by
  // more than the tolerance), or invalid options (naming the field). `coarse`: a coarse level of `mesh` for the
  // two-grid solver (mesh::refine_uniformly, mesh::interpolating_coarse_level); only read here.
  QuasiStaticSolver(const mesh::TetMesh& mesh, std::vector<Indenter> indenters, SolverOptions options = {},
                    const mesh::CoarseLevel* coarse = nullptr);
  ~QuasiStaticSolver();
  QuasiStaticSolver(QuasiStaticSolver&&) noexcept;
  QuasiStaticSolver& operator=(QuasiStaticSolver&&) noexcept;

  // One load step from the last converged state to the needle displacement `indenter_displacement` (m, may be
  // smaller than the current one), with automatic cut-back. Never throws for numerical failure: the result says
  // where and why it stopped, and the solver keeps the last converged state.
  StepResult advance_to(double indenter_displacement);
  // The same step with Newton started from `start` (m, one vector per node of nodes()) instead of the predictor: a
  // warm start from the same step of a run on the same mesh with slightly different parameters (the finite
  // differences of a calibration). The prescribed dofs are set as usual; a start that does not converge is dropped
  // and the step runs as advance_to would. `start` of another size is an std::invalid_argument.
  StepResult advance_to(double indenter_displacement, const std::vector<Eigen::Vector3d>& start);

  double indenter_displacement() const;                    // m, last converged
  const std::vector<Eigen::Vector3d>& nodes() const;       // reference positions: the mesh's nodes, then (T10)
                                                           // one mid-edge node per edge
  const std::vector<Eigen::Vector3d>& displacement() const;  // m, per node of nodes()
  // Element connectivity into nodes(): 4 or 10 indices per tet, VTK order (corners, then the mid-points of edges
  // 01, 12, 20, 03, 13, 23).
  const std::vector<std::vector<int>>& elements() const;
  const std::vector<int>& contact_flag() const;            // per node: 0, or 1 + needle index in contact
  const std::vector<double>& contact_pressure() const;     // Pa, per node (0 where not in contact)
  ElementFields element_fields() const;
  const SolverOptions& options() const;
  int dof_count() const;        // 3 * nodes
  int free_dof_count() const;   // unknowns of the linear systems
  LinearSolver linear_solver() const;  // the one in use (never Automatic)
  // Linear tetrahedra whose volume is averaged at the nodes (VolumetricFormulation), of all elements.
  int nodal_average_elements() const;

  // The total potential energy (strain + contact), its gradient over the free dofs (the residual) and its dense
  // tangent at the displacement `u` (one vector per node of nodes(); prescribed dofs as given) with the needles at
  // `indenter_displacement`: for verification on small meshes (tangent vs finite differences). Uses the solver's
  // work space: call advance_to (which re-evaluates its converged state) before reading outputs again.
  struct Linearization {
    bool valid = true;            // false: an element or a nodal volume inverted
    double energy = 0;            // J
    Eigen::VectorXd gradient;     // N, per free dof, in ascending dof (3 * node + component) order
    Eigen::MatrixXd tangent;      // N/m, free x free (the gradient's order), symmetric
  };
  Linearization linearization(const std::vector<Eigen::Vector3d>& u, double indenter_displacement);

  // Of the Cholesky factor in use (TwoGrid: the coarse level's): its entries (about 8 bytes each) and the
  // floating-point operations of one numeric factorization.
  double factor_nonzeros() const;
  double factor_flops() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace needlekit::fem
