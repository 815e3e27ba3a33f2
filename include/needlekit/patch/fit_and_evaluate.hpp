// The patch pipeline of dissertation ch. 5 and §6.4 as one call: the patch's layout (patch_design), its starting
// frame over the surface (patch_frame), the fit (rigid, node sweeping or equilibrium: fit_patch) and the evaluation
// of every needle (evaluate_needles), optionally with the springs measured along the surface (spring_geodesics).
// `needlekit patch`, `needlekit reproduce` (§6.4) and the Python module call this and only present the result.
#pragma once
#include <functional>
#include <optional>
#include <string>

#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"
#include "needlekit/patch/patch_design.hpp"
#include "needlekit/patch/patch_placement.hpp"
#include "needlekit/patch/spring_geodesics.hpp"

namespace needlekit::patch {

struct FitAndEvaluateOptions {
  Placement placement;                   // where the patch goes on the surface
  FitOptions fit;                        // rigid, flexible (E_cri) or equilibrium
  NeedleEvaluationOptions evaluation;    // tissue, target depth and the index's options
  bool spring_geodesics = false;         // also measure every spring along the surface (beyond the dissertation)
  // Called with the fraction done in [0, 1], never decreasing, from the calling thread: the frame is kFrameShare of
  // it, the fit (node sweeping: each node mapped; equilibrium: each Newton iteration; rigid: one step) the share up
  // to kFitEnd, the evaluation of the needles up to kEvaluationEnd (1 without spring_geodesics), the springs measured
  // along the surface the rest. Return false to stop: fit_and_evaluate throws needlekit::Interrupted. It replaces
  // fit.flexible.progress and fit.equilibrium.progress. May be empty.
  std::function<bool(double)> progress;
  static constexpr double kFrameShare = 0.05;
  static constexpr double kFitEnd = 0.85;
  static constexpr double kEvaluationEnd = 0.95;
};

struct FitAndEvaluateResult {
  FitStatus status = FitStatus::Ok;      // the fit's (a patch that leaves the surface is a status, not an error)
  std::string reason;                    // empty when Ok
  PatchDesign design;
  PatchFrame frame;                      // the starting frame (the fit's frame is fit.frame)
  FittedPatch fit;
  PatchEvaluation evaluation;
  std::optional<SpringGeodesics> geodesics;  // with options.spring_geodesics
  double fit_seconds = 0;                // s, wall time of the fit alone
};

// Throws InvalidInput for an invalid design, placement (a centre off the surface, a surface facing away) or
// evaluation options.
FitAndEvaluateResult fit_and_evaluate(const geometry::SurfaceMesh& surface, const PatchDesignOptions& design,
                                      const FitAndEvaluateOptions& options = {});

}  // namespace needlekit::patch
