#include "needlekit/patch/fit_and_evaluate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "needlekit/core/interrupt.hpp"

namespace needlekit::patch {
namespace {

// options.progress at `fraction` (nothing without one); Interrupted when it returns false.
void report(const FitAndEvaluateOptions& options, double fraction) {
  if (options.progress && !options.progress(fraction)) throw Interrupted();
}

// The fit's options with its progress mapped onto [kFrameShare, kFitEnd] of the pipeline's.
FitOptions fit_options_reporting(const FitAndEvaluateOptions& options) {
  FitOptions fit = options.fit;
  fit.flexible.progress = fit.equilibrium.progress = nullptr;
  if (options.progress) {
    const auto& progress = options.progress;
    const auto scaled = [progress](double fraction) {
      constexpr double start = FitAndEvaluateOptions::kFrameShare, end = FitAndEvaluateOptions::kFitEnd;
      return progress(std::min(end, start + fraction * (end - start)));
    };
    fit.flexible.progress = fit.equilibrium.progress = scaled;
  }
  return fit;
}

}  // namespace

FitAndEvaluateResult fit_and_evaluate(const geometry::SurfaceMesh& surface, const PatchDesignOptions& design,
                                      const FitAndEvaluateOptions& options) {
  FitAndEvaluateResult result;
  report(options, 0);
  result.design = patch_design(design);
  result.frame = patch_frame(surface, options.placement, std::hypot(result.design.width_u, result.design.width_v),
                             result.design.needle.length);
  report(options, FitAndEvaluateOptions::kFrameShare);
  const auto start = std::chrono::steady_clock::now();
  result.fit = fit_patch(surface, result.design, result.frame, fit_options_reporting(options));
  result.fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.status = result.fit.status;
  result.reason = result.fit.reason;
  report(options, FitAndEvaluateOptions::kFitEnd);
  result.evaluation = evaluate_needles(surface, result.design, result.fit, options.evaluation);
  report(options, options.spring_geodesics ? FitAndEvaluateOptions::kEvaluationEnd : 1.0);
  if (options.spring_geodesics) {
    result.geodesics = spring_geodesics(surface, result.design, result.fit);
    report(options, 1);
  }
  return result;
}

}  // namespace needlekit::patch
