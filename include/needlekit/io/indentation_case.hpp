// Indentation case files (TOML) for `needlekit indent`. Every dimensional value is a string with its unit; a bare
// number for a dimensional quantity, an unknown key, a missing required key and an out-of-range value are errors
// that name the file, the line and the key:  FILE:LINE: key 'tissue.layers[2].thickness': <problem>, expected <what>.
//
//   name = "flat punch"                 optional; names the outputs
//   [needle]   either a parametric needle as in design files (shape, tip_diameter, base_diameter, bore_diameter,
//              length; material is accepted and ignored: the needle is rigid), or mesh = "needle.stl" (relative to
//              the case file) with mesh_unit = "um" (the STL in the needle frame: axis z, tip at the largest z);
//              tip_height (default "0 um", >= 0: the tip's height above the surface at the start); segments
//              (default 64) and axial_segments (default 16) of the parametric needle's surface mesh
//   [[needles]]  optional, one entry per needle: x, y (default "0 um"), tip_height (default: [needle]'s);
//              without it, one needle at (0, 0)
//   [array]    optional, instead of [[needles]]: the needle of [needle] repeated (insertion/needle_array.hpp):
//              layout (insertion::kArrayLayoutNames, default "square"), rows, columns (default 1), pitch (default
//              "600 um", >= the needle's base diameter), margin (default "1000 um": the block is the footprint plus
//              the margin on every side unless [tissue] width/length are given), backing_plate (default false),
//              symmetry (insertion::kArraySymmetryNames, default "none")
//   [tissue], [mesh]  as in tissue_config.hpp (shared with `needlekit tissue-mesh`): width, length, height, preset
//              or [[tissue.layers]] (name, thickness or "rest", youngs_modulus, poisson_ratio); size_at_tip,
//              size_far, refinement_radius, size_gradient, thin_layer_size_factor, sites (one needle per site when
//              there is no [[needles]]), split (mesh at twice the sizes and split every tet into eight: the
//              two-grid solver), or file = "tissue.msh" + unit for a user's tetrahedral mesh
//   [loading]  depth (required), steps (default 20), continue_after_puncture (default false)
//   [model]    law (fem::kMaterialLawNames, default "neo-hookean"); contact (fem::kContactModelNames, default
//              "surface"); element (fem::kElementOrderNames, default "linear"); boundary
//              (fem::kBoundaryConditionNames, default "sides-and-bottom-fixed")
//   [solver]   optional Newton settings (fem::SolverOptions): residual_tolerance (default 1e-6),
//              displacement_tolerance (1e-5), energy_tolerance (1e-8), penetration_tolerance (1e-3), all in (0, 1);
//              max_iterations (0: 25, or 60 with surface contact), max_cutbacks (8); predictor (kPredictorNames below, default "secant");
//              linear_solver (fem::kLinearSolverNames, default "auto"; "two-grid" with linear elements needs [mesh]
//              split = true); penalty_factor (100, surface contact); friction (0, surface contact: Coulomb's
//              coefficient); two_pass (false, surface contact: the needle's sharp edges against the tissue's
//              faces too); volumetric_stabilization (1, the
//              nodal-averaged volume of linear tetrahedra at poisson_ratio >= 0.45); threads (0 = all cores)
//   [puncture] critical_pressure (e.g. "0.663 MPa") and/or toughness (e.g. "100 J/m2", also "0.1 kJ/m2", "100 N/m")
//              or toughness_from = { first = "first.csv", second = "second.csv", crack_area = "6661 um2",
//              min_depth, max_depth }: J by the two-insertion method (Eq 3.16) from two force curves (CSV with
//              depth_um,force_N; io/force_curve_csv.hpp) measured at the same spot; crack_area defaults to the
//              parametric needle's tip area
#pragma once
#include <filesystem>
#include <string_view>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/parameter.hpp"
#include "needlekit/insertion/indentation.hpp"

namespace needlekit::io {

// [solver]: the numeric settings of fem::SolverOptions (defaults: its initializers), one declaration each.
inline constexpr Parameter<fem::SolverOptions, double> kSolverTolerances[] = {
    {"residual_tolerance", &fem::SolverOptions::residual_tolerance, 0, 1, Bound::Open, Bound::Open,
     "Newton: residual norm relative to the reaction and internal forces"},
    {"displacement_tolerance", &fem::SolverOptions::displacement_tolerance, 0, 1, Bound::Open, Bound::Open,
     "Newton: update norm relative to the displacement"},
    {"energy_tolerance", &fem::SolverOptions::energy_tolerance, 0, 1, Bound::Open, Bound::Open,
     "Newton: energy norm of the update relative to the first iteration's"},
    {"penetration_tolerance", &fem::SolverOptions::penetration_tolerance, 0, 1, Bound::Open, Bound::Open,
     "surface contact: augmented-Lagrangian updates until the penetration is below this fraction"},
    {"penalty_factor", &fem::SolverOptions::penalty_factor, 0, kNoLimit, Bound::Open,
     Bound::Open, "surface contact: penalty stiffness per area = factor * E / h"},
    {"friction", &fem::SolverOptions::friction, 0, kNoLimit, Bound::Closed, Bound::Open,
     "surface contact: Coulomb friction coefficient between needle and tissue (0: frictionless)"},
    {"volumetric_stabilization", &fem::SolverOptions::volumetric_stabilization, 0, kNoLimit, Bound::Closed,
     Bound::Open, "nodal-averaged volume: the bulk modulus each tetrahedron keeps, in multiples of its shear modulus"},
};
// The help of max_iterations below spells out fem::newton_iteration_limit's defaults.
static_assert(fem::kNewtonIterations == 25 && fem::kSurfaceContactNewtonIterations == 60,
              "update the help text of [solver] max_iterations (and the Python docstring of SolverOptions)");
inline constexpr Parameter<fem::SolverOptions, int> kSolverCounts[] = {
    {"max_iterations", &fem::SolverOptions::max_iterations, 0, kNoLimit, Bound::Closed, Bound::Closed,
     "Newton iterations per (sub)step (0: 25, or 60 with surface contact)"},
    {"max_cutbacks", &fem::SolverOptions::max_cutbacks, 0, kNoLimit, Bound::Closed, Bound::Closed,
     "halvings of a load step that did not converge"},
    {"threads", &fem::SolverOptions::threads, 0, kNoLimit, Bound::Closed, Bound::Closed,
     "assembly threads (0: the default, all cores)"},
};

// [solver] predictor: fem::SolverOptions::extrapolate_predictor.
inline constexpr EnumTable<bool, 2> kPredictorNames{{
    {true, "secant", "later steps start from the converged states extrapolated (quadratically from the third step; default)"},
    {false, "linearised", "§3.4's linearised solve before every step"},
}};

// Throws IoError (unreadable file, TOML syntax, unreadable needle STL) or InvalidInput (a missing, unknown or invalid
// key).
insertion::IndentationCase read_indentation_case(const std::filesystem::path& path);
// The same from text; `source_name` stands for the file name in messages, `base_directory` resolves a relative
// needle mesh path.
insertion::IndentationCase parse_indentation_case_toml(std::string_view text, std::string_view source_name,
                                                       const std::filesystem::path& base_directory = ".");

}  // namespace needlekit::io
