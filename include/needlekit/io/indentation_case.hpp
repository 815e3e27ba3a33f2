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
//   [model], [solver]  the rows of fem::kSolverParameters (fem/solver_parameters.hpp; `needlekit describe --all`,
//              docs/reference.md): [model] law (default "neo-hookean" here), element, contact (default "surface"
//              here), boundary; [solver] Newton tolerances and counts, predictor, surface contact settings (only
//              with contact = "surface"), volumetric, volumetric_stabilization (only where the nodal-averaged volume
//              acts), linear_solver ("two-grid" with linear elements needs [mesh] split = true), backend, threads
//   [puncture] critical_pressure (e.g. "0.663 MPa") and/or toughness (e.g. "100 J/m2", also "0.1 kJ/m2", "100 N/m")
//              or toughness_from = { first = "first.csv", second = "second.csv", crack_area = "6661 um2",
//              min_depth, max_depth }: J by the two-insertion method (Eq 3.16) from two force curves (CSV with
//              depth_um,force_N; io/force_curve_csv.hpp) measured at the same spot; crack_area defaults to the
//              parametric needle's tip area
#pragma once
#include <filesystem>
#include <string_view>

#include "needlekit/fem/solver_options.hpp"
#include "needlekit/insertion/indentation.hpp"

namespace needlekit::io {

// The solver options a case file starts from: SolverOptions' defaults with the neo-Hookean law and surface contact.
fem::SolverOptions case_solver_defaults();

// Throws IoError (unreadable file, TOML syntax, unreadable needle STL) or InvalidInput (a missing, unknown or invalid
// key).
insertion::IndentationCase read_indentation_case(const std::filesystem::path& path);
// The same from text; `source_name` stands for the file name in messages, `base_directory` resolves a relative
// needle mesh path.
insertion::IndentationCase parse_indentation_case_toml(std::string_view text, std::string_view source_name,
                                                       const std::filesystem::path& base_directory = ".");

}  // namespace needlekit::io
