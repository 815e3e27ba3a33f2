// Outputs of a patch fit: the per-needle CSV and the JSON summary (units in every column and key), and the ParaView
// grids of the surface near the patch, the fitted patch (nodes; springs coloured by strain energy) and the needles
// (segments coloured by buckling force, bending force, angle, failure and performance index: the colour maps of
// Figs 6.21–6.27).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/io/vtu_writer.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"

namespace needlekit::io {

// One row per needle: node, i, j, inner, on_surface, base/tip/surface point (mm), travel_um, penetration_um,
// angle_deg, buckling_force_N, bending_force_N, penetrates, buckles, bends, local_pitch_um,
// performance_index_per_um, status.
std::string patch_needles_csv(const patch::PatchDesign& design, const patch::FittedPatch& fit,
                              const patch::PatchEvaluation& evaluation);

// needles, penetrating, buckled, bent, on_surface, performance_index_mean_per_um, performance_index_total_per_um,
// performance_index_per_um / buckling_force_N / bending_force_N / angle_deg / travel_um as {min, max, mean},
// spring_energy_mJ {min, max, mean, total}, critical loads, F(A), d, status, reason, affected_nodes, fit_ms.
nlohmann::json patch_summary_json(const patch::PatchDesign& design, const patch::FitOptions& fit_options,
                                  const patch::FittedPatch& fit, const patch::PatchEvaluation& evaluation,
                                  double fit_ms);

// The failure code of a needle in the VTU field "failure": 0 ok, 1 short (x <= d), 2 buckles, 3 bends,
// 4 no surface under it, 5 too shallow (x − d < T).
int failure_code(const patch::NeedleState& needle);

// The triangles with a vertex within `radius` of `center` (all of them when radius is infinite).
VtuGrid surface_grid(const geometry::SurfaceMesh& surface, const Eigen::Vector3d& center, double radius);
// Nodes (point field on_surface) and springs as lines (cell fields strain_energy_mJ, stretch_um, direction, and
// geodesic_strain when given: patch::spring_geodesics().strain, one per spring).
VtuGrid patch_grid(const patch::PatchDesign& design, const patch::FittedPatch& fit,
                   const std::vector<double>& geodesic_strain = {});
// Needles as base→tip segments with cell fields buckling_force_N, bending_force_N, angle_deg, failure,
// performance_index_per_um, travel_um, penetration_um.
VtuGrid needles_grid(const patch::PatchEvaluation& evaluation);

}  // namespace needlekit::io
