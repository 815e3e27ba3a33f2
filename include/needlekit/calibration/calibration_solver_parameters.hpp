// calibration::SolverSettings' parameter table (core/parameter.hpp): one row per field, declared here once; the
// defaults are the struct's initializers (calibration_problem.hpp). Calibration files write them in [solver]. The
// calibration file reader, `needlekit calibrate --help`, `needlekit describe`, docs/reference.md, the validation in
// calibrate() and Python's CalibrationSolverSettings read this table; tests/unit/test_parameter_tables.cpp checks
// that every field has a row.
//
// A new parameter: its field with its initializer in SolverSettings, and one row here.
#pragma once
#include <tuple>

#include "needlekit/calibration/calibration_problem.hpp"
#include "needlekit/core/parameter.hpp"

namespace needlekit::calibration {

inline constexpr std::tuple kCalibrationSolverParameters{
    Parameter<SolverSettings, int>{"max_iterations", &SolverSettings::max_iterations, 1, kNoLimit, Bound::Closed,
                                   Bound::Closed, "Levenberg-Marquardt iterations (Ceres)", "solver"},
    Parameter<SolverSettings, double>{"relative_step", &SolverSettings::relative_step, 0, 0.1, Bound::Closed,
                                      Bound::Open,
                                      "finite-difference step relative to each parameter (0: automatic, 1e-7 for "
                                      "analytic experiments only, 1e-3 when an FE run is involved)",
                                      "solver"},
    Parameter<SolverSettings, double>{"function_tolerance", &SolverSettings::function_tolerance, 0, 1, Bound::Open,
                                      Bound::Open, "relative decrease of the cost that counts as converged",
                                      "solver"},
    Parameter<SolverSettings, double>{"parameter_tolerance", &SolverSettings::parameter_tolerance, 0, 1, Bound::Open,
                                      Bound::Open, "relative step size that counts as converged", "solver"},
    Flag<SolverSettings>{"mesh_error", &SolverSettings::mesh_error,
                         "widen the 95 % intervals by the estimated FE discretisation error (one finer run per FE "
                         "experiment; discretisation_error.hpp)",
                         "solver"},
    Parameter<SolverSettings, double>{"mesh_error_refinement", &SolverSettings::mesh_error_refinement, 0, 1,
                                      Bound::Open, Bound::Open,
                                      "the finer meshes' element sizes relative to the fit's (mesh_error)", "solver"},
};
static_assert(std::tuple_size_v<decltype(kCalibrationSolverParameters)> == field_count<SolverSettings>(),
              "every field of calibration::SolverSettings has a row");

}  // namespace needlekit::calibration
