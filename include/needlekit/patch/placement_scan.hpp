// Where to put the patch (dissertation §6.4.2: "it is recommended that a microneedle patch ... is to be placed on a
// relatively flat area of skin"): fit and evaluate the patch centred on each of many surface vertices, in
// parallel, and report each placement's summary.
#pragma once
#include <functional>
#include <vector>

#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"

namespace needlekit::patch {

struct PlacementScanOptions {
  FitOptions fit;                        // how every placement is fitted
  NeedleEvaluationOptions evaluation;    // how its needles are evaluated
  Approach approach = Approach::SurfaceNormal;  // per placement (−Z only reaches the front of a body)
  double rotation = 0;                   // rad, as Placement::rotation
  std::function<void(double)> progress;  // called with the fraction done, from worker threads (may be empty)
};

struct PlacementSummary {
  int vertex = -1;
  FitStatus status = FitStatus::Ok;
  bool placed = false;                   // false when the frame could not be built (e.g. a vertex facing away)
  int penetrating = 0, buckled = 0, bent = 0;
  double performance_index_mean = 0;     // 1/m
  double angle_max = 0;                  // rad
  double bending_force_max = 0;          // N
  double spring_energy_total = 0;        // J
};

// One summary per vertex, in the given order (TBB threads; SurfaceMesh queries are const).
std::vector<PlacementSummary> placement_scan(const geometry::SurfaceMesh& surface, const PatchDesign& design,
                                             const std::vector<int>& vertices, const PlacementScanOptions& options = {});

}  // namespace needlekit::patch
