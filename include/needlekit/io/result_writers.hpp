// Results as JSON and CSV, in the dissertation's units (um, um^2, um^3, N, GPa, 1/um) with the unit in every key or
// column name, and an atomic text-file writer so that a failed run leaves no partial file.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/analysis/sensitivity_sweep.hpp"

namespace needlekit::io {

// Every quantity of the evaluation and the inputs of the design (shape, diameters, length, material, E, n, width).
// Keys that were not assessed (critical_bending_load_N, bending_ok without an allowable stress) are null.
nlohmann::json performance_json(const analysis::ArrayDesign& design, const analysis::PerformanceIndexResult& result);

// {"needles_per_row", "tip_diameter_um", ..., "performance_index_per_um"} of one optimizer candidate.
nlohmann::json candidate_json(const analysis::DesignCandidate& candidate);

// {"shape", "hollow", "material", "best", "evaluated", "feasible", "grid_points", "seconds", "status", "reason",
//  "top": [... + "details"]}; "best" is null when no design is feasible. The space supplies the needle type and
// the material of the candidates' details.
nlohmann::json optimizer_json(const analysis::DesignSpace& space, const analysis::OptimizerResult& result);

// The unit in which a swept parameter is reported: "um", "deg", or "" for needles_per_row.
std::string_view sweep_report_unit(analysis::SweepParameter parameter);
// The column (and JSON key) name of the swept value, e.g. "base_diameter_um", "needles_per_row".
std::string sweep_value_column(analysis::SweepParameter parameter);

// One header line and one row per point: the swept value, performance_index_per_um, status, deformation_um,
// cutting_depth_um, Q_um2, puncture_force_N, critical_buckling_load_N, buckling_force_N, reason (RFC 4180 quoting).
std::string sweep_csv(const analysis::SweepResult& sweep);
// {"parameter", "unit", "points": [{<value column>, "details": performance_json}]}.
nlohmann::json sweep_json(const analysis::SweepResult& sweep);

// needlekit::write_file_atomically (core/atomic_file.hpp): `content` goes to a temporary file next to `path`, renamed
// to `path` when complete; IoError naming the path on failure.
void write_text_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace needlekit::io
