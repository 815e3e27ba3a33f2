// A patch after fitting: node positions and normals, the spring energies of Eq 5.13 and the fit's status. Shared
// by the rigid fit, the node-sweeping fit (Alg 5.1–5.3) and the equilibrium fit.
#pragma once
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/patch/patch_design.hpp"
#include "needlekit/patch/patch_placement.hpp"

namespace needlekit::patch {

enum class FitStatus {
  Ok,
  BoundaryReached,   // a traverse or a needle ran off the surface's boundary: `affected_nodes` name them
  DegenerateSurface, // a traverse met a degenerate triangle and stopped there
  EnergyCapExceeded, // some springs could not be kept under E_cri (they are named; the fit is otherwise complete)
  NotConverged,      // the equilibrium solver stopped at its iteration limit
  MissesSurface,     // the patch does not reach the surface at all
};
inline constexpr EnumTable<FitStatus, 6> kFitStatusNames{{
    {FitStatus::Ok, "ok", "the patch was fitted"},
    {FitStatus::BoundaryReached, "boundary_reached", "a traverse or a needle ran off the surface's boundary"},
    {FitStatus::DegenerateSurface, "degenerate_surface", "a traverse met a degenerate triangle and stopped there"},
    {FitStatus::EnergyCapExceeded, "energy_cap_exceeded", "some springs could not be kept under E_cri"},
    {FitStatus::NotConverged, "not_converged", "the equilibrium solver stopped at its iteration limit"},
    {FitStatus::MissesSurface, "misses_surface", "the patch does not reach the surface at all"},
}};
std::string_view to_string(FitStatus status);

struct FittedPatch {
  std::vector<Eigen::Vector3d> positions;  // m, one per node
  std::vector<Eigen::Vector3d> normals;    // unit, away from the surface; each needle points along −normal
  std::vector<bool> on_surface;            // the node lies on the surface (within the fit's tolerance)
  PatchFrame frame;
  FitStatus status = FitStatus::Ok;
  std::string reason;                      // empty when Ok
  std::vector<int> affected_nodes;         // nodes named by the status
  int first_node = -1;                     // the node mapped first (node sweeping) or the first contact (rigid)
  int iterations = 0;                      // solver iterations (equilibrium fit)
};

// The rest (flat, t = 0) position of every node in the patch frame, lifted `height` along −approach above the
// surface point.
std::vector<Eigen::Vector3d> flat_positions(const PatchDesign& design, const PatchFrame& frame, double height);

// Eqs 5.13, 5.14 (notes: the cap is per spring): ½·K·ΔL² of every spring, ΔL = |L^t − L^{t=0}| (J).
std::vector<double> spring_energies(const PatchDesign& design, const std::vector<Eigen::Vector3d>& positions);

// Unit normals of the deformed grid (central differences along U and V, one-sided at the edges), oriented against
// `approach`.
std::vector<Eigen::Vector3d> grid_normals(const PatchDesign& design, const std::vector<Eigen::Vector3d>& positions,
                                          const Eigen::Vector3d& approach);

}  // namespace needlekit::patch
