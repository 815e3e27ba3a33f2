// Per-needle evaluation of a fitted patch (dissertation §5.2–5.3, §6.4). For every needle (base at its node, axis
// along −node normal, tip at base + L·axis):
//   N_int  the intersection of the needle's axis with the surface,
//   x_ij   = ‖N_tip − N_int‖, the travel of the tip beyond the surface (Eq 5.12; negative when the tip stops short),
//   x − d  the penetration beyond the tissue deformation d before puncture (Eq 5.11 / 4.3),
//   θ      the angle between the needle axis and the surface normal at N_int,
//   |F|/cos θ and |F|·tan θ, the buckling and bending forces (Eqs 5.2–5.4) against P_cr and P_Be (Eqs 5.5–5.8),
//   φ, ω   and the needle's performance index φ·ω·Q(h)/(Pxy²·H) (Eq 5.9) with the cutting depth h = min(x, L) − d.
// The patch summary gives min, max, mean and total as in §6.4.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/patch/fitted_patch.hpp"

namespace needlekit::patch {

struct NeedleEvaluationOptions {
  analysis::InsertionConditions conditions;    // tissue (α, τ), target depth T; the angle field is ignored
  analysis::PerformanceIndexOptions index;     // buckling options and safety factors (spacing constraint ignored)
  bool local_pitch = false;  // false: Pxy = w/n in every needle's index (Eq 5.9); true: the needle's local pitch
};

struct NeedleState {
  Eigen::Vector3d base, tip, axis;          // m, m, unit (from base to tip)
  bool hits_surface = false;                // the axis meets the surface near the needle
  Eigen::Vector3d surface_point = Eigen::Vector3d::Zero();  // m, N_int
  Eigen::Vector3d surface_normal = Eigen::Vector3d::Zero(); // unit, at N_int
  double travel = 0;            // m, x_ij (Eq 5.12), signed: < 0 when the tip does not reach the surface
  double penetration = 0;       // m, x − d
  double angle = 0;             // rad, θ
  double buckling_force = 0;    // N, |F|/cos θ (Eq 5.3)
  double bending_force = 0;     // N, |F|·tan θ (Eq 5.4)
  bool penetrates = false;      // x > d
  bool buckles = false;         // φ = 0
  bool bends = false;           // ω = 0
  double local_pitch = 0;       // m, mean distance to the node's axial neighbours
  double performance_index = 0; // 1/m
  std::string status;           // "ok", "no_surface", "short" (x <= d), "too_shallow" (x − d < T), "buckles", "bends"
};

struct Statistics {
  double min = 0, max = 0, mean = 0, total = 0;
  int count = 0;
};

struct PatchEvaluation {
  std::vector<NeedleState> needles;
  analysis::PerformanceIndexResult reference;  // the analytic evaluation of one needle at θ = 0, fully inserted
  int penetrating = 0, buckled = 0, bent = 0, on_surface = 0;
  Statistics buckling_force, bending_force, angle, travel, performance_index;  // over needles that meet the surface
  Statistics spring_energy;                                                    // J, over springs (Eq 5.13)
};

// Throws InvalidInput for invalid tissue or options (as analysis::performance_index).
PatchEvaluation evaluate_needles(const geometry::SurfaceMesh& surface, const PatchDesign& design,
                                 const FittedPatch& fit, const NeedleEvaluationOptions& options = {});

Statistics statistics(const std::vector<double>& values);

}  // namespace needlekit::patch
