#include "needlekit/patch/needle_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "needlekit/analysis/bending.hpp"
#include "needlekit/analysis/skin_permeation.hpp"

namespace needlekit::patch {

Statistics statistics(const std::vector<double>& values) {
  Statistics s;
  s.count = static_cast<int>(values.size());
  if (values.empty()) return s;
  s.min = std::numeric_limits<double>::infinity();
  s.max = -s.min;
  for (const double v : values) {
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    s.total += v;
  }
  s.mean = s.total / s.count;
  return s;
}

namespace {

// The local pitch of needle k: the mean distance to its axial neighbours.
double local_pitch(const PatchDesign& design, const FittedPatch& fit, int k) {
  const int i = design.column(k), j = design.row(k);
  double sum = 0;
  int count = 0;
  for (const auto& [a, b] : {std::pair{i + 1, j}, std::pair{i - 1, j}, std::pair{i, j + 1}, std::pair{i, j - 1}}) {
    if (a < 0 || b < 0 || a >= design.nodes_u || b >= design.nodes_v) continue;
    sum += (fit.positions[design.node(a, b)] - fit.positions[k]).norm();
    ++count;
  }
  return sum / count;
}

// What the reference needle (straight insertion, performance_index) gives every needle of the patch.
struct Reference {
  double force = 0;        // F(A), Eq 5.1 / 4.2
  double deformation = 0;  // d, Eq 5.11 / 4.3
  double critical_buckling = 0;
  std::optional<double> critical_bending;
  double array_pitch = 0;
};

// Needle s where its axis meets the surface: its travel (Eq 5.12), angle, forces (Eqs 5.3, 5.4), checks and, when
// it inserts, its own index (Eq 5.9 with h = min(x, L) − d, Eq 4.4, and H, Eq 4.23).
void evaluate_hit(const geometry::SurfaceMesh& surface, const geometry::RayHit& hit, const PatchDesign& design,
                  const Reference& ref, const NeedleEvaluationOptions& options, NeedleState& s) {
  const double length = design.needle.length;
  s.hits_surface = true;
  s.surface_point = hit.point;
  const geometry::ClosestPoint cp = surface.closest_point(hit.point);
  s.surface_normal = surface.interpolated_normal(cp.triangle, cp.barycentric);
  s.travel = 2 * length - hit.distance;  // Eq 5.12, signed
  s.penetration = s.travel - ref.deformation;
  s.angle = std::acos(std::clamp(-s.axis.dot(s.surface_normal), -1.0, 1.0));
  const double safe_angle = std::min(s.angle, 0.5 * M_PI * (1 - 1e-12));
  s.buckling_force = analysis::angled_buckling_force(ref.force, safe_angle);  // Eq 5.3
  s.bending_force = analysis::angled_bending_force(ref.force, safe_angle);    // Eq 5.4
  const bool touches = s.travel > 0;
  s.buckles = touches && !(options.index.buckling_safety_factor * s.buckling_force < ref.critical_buckling);
  s.bends = touches && ref.critical_bending &&
            !(options.index.bending_safety_factor * s.bending_force < *ref.critical_bending);
  s.penetrates = s.travel > ref.deformation;
  if (!s.penetrates) {
    s.status = "short";
  } else if (s.buckles) {
    s.status = "buckles";
  } else if (s.bends) {
    s.status = "bends";
  } else {
    const double inserted = std::min(s.travel, length);
    const double depth = analysis::ideal_permeation_depth(design.needle.hollow(), inserted, ref.deformation,
                                                          options.conditions.target_depth);
    if (depth <= 0) {
      s.status = "too_shallow";
    } else {
      const double cutting = inserted - ref.deformation;
      const double pitch = options.local_pitch ? s.local_pitch : ref.array_pitch;
      s.performance_index = analysis::permeation_factor(design.needle, cutting) / (pitch * pitch * depth);
      s.status = "ok";
    }
  }
}

}  // namespace

PatchEvaluation evaluate_needles(const geometry::SurfaceMesh& surface, const PatchDesign& design,
                                 const FittedPatch& fit, const NeedleEvaluationOptions& options) {
  PatchEvaluation result;
  analysis::ArrayDesign array{design.needle, design.material, design.nodes_u, design.width_u};
  analysis::InsertionConditions straight = options.conditions;
  straight.angle = 0;
  analysis::PerformanceIndexOptions index = options.index;
  index.spacing_factor = 0;  // the patch's own pitch is given; §4.8's spacing constraint is a design rule
  result.reference = analysis::performance_index(array, straight, index);
  const Reference ref{result.reference.puncture_force, result.reference.deformation,
                      result.reference.buckling.critical_load, result.reference.critical_bending_load,
                      std::sqrt(design.pitch_u * design.pitch_v)};
  const double length = design.needle.length;
  const int n = design.node_count();
  result.needles.resize(n);
  std::vector<double> buckling, bending, angle, travel, index_values;
  for (int k = 0; k < n; ++k) {
    NeedleState& s = result.needles[k];
    s.base = fit.positions[k];
    s.axis = -fit.normals[k];
    s.tip = s.base + length * s.axis;
    s.local_pitch = local_pitch(design, fit, k);
    // N_int: the axis, cast from one needle length behind the base.
    const auto hit = surface.first_hit(s.base - length * s.axis, s.axis);
    if (!hit) {
      s.status = "no_surface";
      index_values.push_back(0);
      continue;
    }
    evaluate_hit(surface, *hit, design, ref, options, s);
    buckling.push_back(s.buckling_force);
    bending.push_back(s.bending_force);
    angle.push_back(s.angle);
    travel.push_back(s.travel);
    index_values.push_back(s.performance_index);
    if (s.penetrates) ++result.penetrating;
    if (s.buckles) ++result.buckled;
    if (s.bends) ++result.bent;
  }
  for (int k = 0; k < n; ++k) result.on_surface += fit.on_surface.empty() ? 0 : fit.on_surface[k];
  result.buckling_force = statistics(buckling);
  result.bending_force = statistics(bending);
  result.angle = statistics(angle);
  result.travel = statistics(travel);
  result.performance_index = statistics(index_values);
  result.spring_energy = statistics(spring_energies(design, fit.positions));
  return result;
}

}  // namespace needlekit::patch
