// A calibration problem: the parameters to fit (paths into the experiments' case files, with initial values and
// bounds) and the experiments with their measured data, as read from a calibration file (TOML):
//
//   name = "phantom"                                    optional; names the outputs (default: the file's stem)
//   [solver]                                            optional
//   max_iterations = 30        relative_step = 1e-3     function_tolerance = 1e-10     parameter_tolerance = 1e-10
//   mesh_error = true          mesh_error_refinement = 0.75
//   [[parameters]]
//   path = "tissue.layers.0.youngs_modulus"             a key of the experiments' case files (parameter_kinds())
//   initial = "0.1 MPa"                                  with the unit of the key's dimension (a number if the key is)
//   bounds = ["0.01 MPa", "10 MPa"]                      lower < upper, lower <= initial <= upper
//   [[experiments]]
//   name = "sharp"
//   case = "insert_sharp_bevel.toml"                     an indent or insert case, or a design file; relative to this file
//   measured = "sharp_curve.csv"                         depth_<unit>, force_<unit> (>= 3 samples); and/or
//   puncture = { depth = "230 um", force = "0.014 N" }  the measured puncture point (design files: d and F(A))
//   weights = { curve = 1.0, puncture = 1.0 }            optional, >= 0; all 0: a prediction (run once at the
//                                                        fitted values and reported beside its data, not fitted)
//
// Errors name the calibration file, the line and the key (or the case file and the key), as the other readers.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/insertion/force_curve.hpp"

namespace needlekit::calibration {

struct ParameterSpec {
  std::string path;                  // dotted TOML path in the case files, e.g. "puncture.critical_pressure"
  units::Dimension dimension = units::Dimension::Dimensionless;
  std::string unit;                  // the unit the user gave `initial` in ("MPa"; "" for a number): for presenting
  double initial = 0;                // SI
  double lower = 0, upper = 0;       // SI, lower <= initial <= upper, lower < upper
  std::string where;                 // "FILE:LINE: parameters[k]" for messages
};

enum class ExperimentKind {
  Design,       // a design file: the analytic model (§4.2), measured puncture force F(A) and/or deformation d
  Indentation,  // an indent case: the FE curve (continued past puncture) and the puncture point
  Insertion,    // an insert case: the complete curve (FE to puncture, then the cutting force) and the puncture point
};
inline constexpr EnumTable<ExperimentKind, 3> kExperimentKindNames{{
    {ExperimentKind::Design, "design", "a design file: the analytic model (§4.2)"},
    {ExperimentKind::Indentation, "indent", "an indent case: the FE curve and the puncture point"},
    {ExperimentKind::Insertion, "insert", "an insert case: the complete curve and the puncture point"},
}};
std::string_view to_string(ExperimentKind kind);

struct MeasuredPuncture {
  std::optional<double> depth;  // m (design files: the deformation d before puncture)
  std::optional<double> force;  // N
};

struct ExperimentSpec {
  std::string name;
  std::filesystem::path case_path;
  std::string case_text;                             // the case file as read
  ExperimentKind kind = ExperimentKind::Insertion;
  std::optional<std::filesystem::path> measured_path;
  std::optional<insertion::ForceDepthCurve> measured;  // SI
  MeasuredPuncture puncture;
  double curve_weight = 1;
  double puncture_weight = 1;
  std::string where;                                  // "FILE:LINE: experiments[k]"
};

struct SolverSettings {
  int max_iterations = 30;             // >= 1, Levenberg-Marquardt iterations
  double relative_step = 0;            // (0, 0.1): finite-difference step relative to each parameter; 0 = automatic
                                       // (1e-7 for analytic experiments only, 1e-3 when an FE run is involved)
  double function_tolerance = 1e-10;   // (0, 1): relative decrease of the cost that counts as converged
  double parameter_tolerance = 1e-10;  // (0, 1): relative step size that counts as converged
  bool mesh_error = true;              // widen the 95 % intervals by the estimated discretisation error of the FE
                                       // experiments (discretisation_error.hpp; one finer run per FE experiment)
  double mesh_error_refinement = 0.75; // (0, 1): the finer meshes' element sizes relative to the fit's
};

struct CalibrationProblem {
  std::string name = "calibration";
  std::filesystem::path file;           // the calibration file
  std::vector<ParameterSpec> parameters;
  std::vector<ExperimentSpec> experiments;
  SolverSettings solver;
};

// Reads and checks the file: every parameter path is a calibratable key (parameter_kinds()) and exists in at least
// one experiment's case with the dimension of its initial value; bounds contain the initial value; every experiment
// has a readable case and measured data (curves: >= 3 samples, increasing depth, depth_/force_ columns). Throws
// IoError or InvalidInput naming FILE:LINE and the key.
CalibrationProblem read_calibration_file(const std::filesystem::path& path);
// The same for a file's text: `source_name` names it in messages, `base_folder` resolves its case and curve paths.
CalibrationProblem parse_calibration_toml(std::string_view text, std::string_view source_name,
                                          const std::filesystem::path& base_folder);

}  // namespace needlekit::calibration
