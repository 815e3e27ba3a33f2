#include "needlekit/patch/fit_and_evaluate.hpp"

#include <chrono>
#include <cmath>

namespace needlekit::patch {

FitAndEvaluateResult fit_and_evaluate(const geometry::SurfaceMesh& surface, const PatchDesignOptions& design,
                                      const FitAndEvaluateOptions& options) {
  FitAndEvaluateResult result;
  result.design = patch_design(design);
  result.frame = patch_frame(surface, options.placement, std::hypot(result.design.width_u, result.design.width_v),
                             result.design.needle.length);
  const auto start = std::chrono::steady_clock::now();
  result.fit = fit_patch(surface, result.design, result.frame, options.fit);
  result.fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.status = result.fit.status;
  result.reason = result.fit.reason;
  result.evaluation = evaluate_needles(surface, result.design, result.fit, options.evaluation);
  if (options.spring_geodesics) result.geodesics = spring_geodesics(surface, result.design, result.fit);
  return result;
}

}  // namespace needlekit::patch
