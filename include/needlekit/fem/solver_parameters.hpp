// fem::SolverOptions' parameter table (core/parameter.hpp): one row per field, declared here once. The defaults are
// the struct's initializers (solver_options.hpp); case files write the rows of group "model" in [model] and those of
// "solver" in [solver]. SolverOptions::validate, the case reader, `needlekit indent --help`, `needlekit describe`,
// docs/reference.md and Python's SolverOptions all read this table; tests/unit/test_parameter_tables.cpp checks that
// every field has a row.
//
// A new parameter: its field with its initializer in SolverOptions, and one row here.
#pragma once
#include <tuple>

#include "needlekit/core/parameter.hpp"
#include "needlekit/fem/solver_options.hpp"

namespace needlekit::fem {

// [solver] predictor: SolverOptions::extrapolate_predictor.
inline constexpr EnumTable<bool, 2> kPredictorNames{{
    {true, "secant", "later steps start from the converged states extrapolated (quadratically from the third step; default)"},
    {false, "linearised", "§3.4's linearised solve before every step"},
}};

// The help of max_iterations spells out newton_iteration_limit's defaults.
static_assert(kNewtonIterations == 25 && kSurfaceContactNewtonIterations == 60,
              "update the meaning of max_iterations below");

inline constexpr std::tuple kSolverParameters{
    // [model]
    Choice<SolverOptions, MaterialLaw, 2>{"law", &SolverOptions::law, &kMaterialLawNames, "constitutive law", "model"},
    Choice<SolverOptions, ElementOrder, 2>{"element", &SolverOptions::order, &kElementOrderNames, "element order",
                                           "model", "order"},
    Choice<SolverOptions, ContactModel, 2>{"contact", &SolverOptions::contact, &kContactModelNames,
                                           "how the needle touches the tissue", "model"},
    Choice<SolverOptions, BoundaryCondition, 6>{"boundary", &SolverOptions::boundary, &kBoundaryConditionNames,
                                                "the supports on the faces of the mesh's bounding box", "model"},
    // [solver]: Newton
    Parameter<SolverOptions, double>{"residual_tolerance", &SolverOptions::residual_tolerance, 0, 1, Bound::Open,
                                     Bound::Open, "Newton: residual norm relative to the reaction and internal forces",
                                     "solver"},
    Parameter<SolverOptions, double>{"displacement_tolerance", &SolverOptions::displacement_tolerance, 0, 1,
                                     Bound::Open, Bound::Open, "Newton: update norm relative to the displacement",
                                     "solver"},
    Parameter<SolverOptions, double>{"energy_tolerance", &SolverOptions::energy_tolerance, 0, 1, Bound::Open,
                                     Bound::Open, "Newton: energy norm of the update relative to the first iteration's",
                                     "solver"},
    Parameter<SolverOptions, int>{"max_iterations", &SolverOptions::max_iterations, 0, kNoLimit, Bound::Closed,
                                  Bound::Closed, "Newton iterations per (sub)step (0: 25, or 60 with surface contact)",
                                  "solver"},
    Parameter<SolverOptions, int>{"max_cutbacks", &SolverOptions::max_cutbacks, 0, kNoLimit, Bound::Closed,
                                  Bound::Closed, "halvings of a load step that did not converge", "solver"},
    Flag<SolverOptions>{"line_search", &SolverOptions::line_search,
                        "backtracking (Armijo) on the potential energy, with a tangent shift when the factorization "
                        "is not positive definite",
                        "solver"},
    Flag<SolverOptions>{"linear_predictor", &SolverOptions::linear_predictor,
                        "the first step starts from the linearised elastic solution (§3.4); false: from the previous "
                        "displacement",
                        "solver"},
    Choice<SolverOptions, bool, 2>{"predictor", &SolverOptions::extrapolate_predictor, &kPredictorNames,
                                   "how the steps after the first start", "solver", "extrapolate_predictor"},
    // [solver]: surface contact
    Parameter<SolverOptions, double>{"penalty_factor", &SolverOptions::penalty_factor, 0, kNoLimit, Bound::Open,
                                     Bound::Open, "surface contact: penalty stiffness per area = factor * E / h",
                                     "solver"},
    Parameter<SolverOptions, double>{"penetration_tolerance", &SolverOptions::penetration_tolerance, 0, 1,
                                     Bound::Open, Bound::Open,
                                     "surface contact: augmented-Lagrangian updates until the penetration is below "
                                     "this fraction",
                                     "solver"},
    Parameter<SolverOptions, int>{"max_augmentations", &SolverOptions::max_augmentations, 0, kNoLimit, Bound::Closed,
                                  Bound::Closed, "surface contact: augmented-Lagrangian updates per step (0: pure penalty)",
                                  "solver"},
    Parameter<SolverOptions, double>{"friction", &SolverOptions::friction, 0, kNoLimit, Bound::Closed, Bound::Open,
                                     "surface contact: Coulomb friction coefficient between needle and tissue (0: "
                                     "frictionless)",
                                     "solver"},
    Flag<SolverOptions>{"two_pass", &SolverOptions::two_pass,
                        "surface contact: the needle's sharp edges and vertices against the tissue's faces too",
                        "solver"},
    // [solver]: volumes, supports
    Choice<SolverOptions, VolumetricFormulation, 3>{"volumetric", &SolverOptions::volumetric,
                                                    &kVolumetricFormulationNames,
                                                    "how linear tetrahedra integrate the volumetric term", "solver"},
    Parameter<SolverOptions, double>{"volumetric_stabilization", &SolverOptions::volumetric_stabilization, 0, kNoLimit,
                                     Bound::Closed, Bound::Open,
                                     "nodal-averaged volume: the bulk modulus each tetrahedron keeps, in multiples of "
                                     "its shear modulus",
                                     "solver"},
    Parameter<SolverOptions, double>{"boundary_tolerance", &SolverOptions::boundary_tolerance, 0, kNoLimit,
                                     Bound::Closed, Bound::Open,
                                     "a node is on a face of the bounding box within this distance (plus 1e-9 of the "
                                     "box diagonal)",
                                     "solver", units::Dimension::Length},
    // [solver]: linear solves
    Choice<SolverOptions, LinearSolver, 4>{"linear_solver", &SolverOptions::linear_solver, &kLinearSolverNames,
                                           "the built-in backend's linear solver", "solver"},
    Choice<SolverOptions, SolverBackend, 2>{"backend", &SolverOptions::backend, &kSolverBackendNames,
                                            "where the linear solves run", "solver"},
    Parameter<SolverOptions, int>{"two_grid_refresh_iterations", &SolverOptions::two_grid_refresh_iterations, 1,
                                  kNoLimit, Bound::Closed, Bound::Closed,
                                  "two-grid: the coarse operator is renewed after a solve that needed more CG "
                                  "iterations (the PETSc backend: its preconditioner)",
                                  "solver"},
    Parameter<SolverOptions, int>{"max_reuse_iterations", &SolverOptions::max_reuse_iterations, 1, kNoLimit,
                                  Bound::Closed, Bound::Closed,
                                  "cholesky-cg: cap on the CG iterations of one solve on the last factorization",
                                  "solver"},
    Parameter<SolverOptions, double>{"linear_tolerance", &SolverOptions::linear_tolerance, 0, 1, Bound::Open,
                                     Bound::Open, "tightest relative residual of CG (inexact Newton stops earlier)",
                                     "solver"},
    Parameter<SolverOptions, int>{"threads", &SolverOptions::threads, 0, kNoLimit, Bound::Closed, Bound::Closed,
                                  "assembly threads (0: the default, all cores)", "solver"},
    // [solver]: rezoning
    Flag<SolverOptions>{"rezone", &SolverOptions::rezone,
                        "surface contact: mesh the deformed tissue anew when a step crushes it or fails", "solver"},
    Parameter<SolverOptions, double>{"rezone_volume_ratio", &SolverOptions::rezone_volume_ratio, 0, 1, Bound::Open,
                                     Bound::Open, "rezone after a step whose smallest element J = det F is below this",
                                     "solver"},
    Parameter<SolverOptions, int>{"max_remeshes", &SolverOptions::max_remeshes, 1, kNoLimit, Bound::Closed,
                                  Bound::Closed, "rezonings per run at most", "solver"},
};
// Fields that are not parameters: progress (a callback).
inline constexpr std::size_t kSolverCallbackFields = 1;
static_assert(field_count<SolverOptions>() == std::tuple_size_v<decltype(kSolverParameters)> + kSolverCallbackFields,
              "a field of SolverOptions has no row in kSolverParameters (or a row too many)");

}  // namespace needlekit::fem
