#include "needlekit/insertion/complete_insertion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::insertion {
namespace {

// The pre-puncture curve of needle i of an FE run: its own reaction force against its own depth (the FE depth is
// measured from the first needle's contact; needle i touches `offset` later), from (0, 0), and its own puncture
// point (NeedleOutcome: the criteria on its own force, area and energy; an array's run goes on until every needle
// has punctured), or none if it did not puncture within the run. A run that records no needles gives every needle
// the run's puncture point.
PrePunctureCurve needle_pre_puncture_curve(const IndentationResult& result, std::size_t i, double offset) {
  PrePunctureCurve pre;
  pre.curve.depth.push_back(0);
  pre.curve.force.push_back(0);
  for (const IndentationStep& step : result.steps) {
    const double x = step.depth - offset;
    if (x <= 0) continue;
    pre.curve.depth.push_back(x);
    pre.curve.force.push_back(i < step.needle_force.size() ? step.needle_force[i] : step.force);
  }
  if (pre.curve.depth.size() < 2) return pre;
  if (i < result.needles.size()) {
    if (const std::optional<PuncturePoint>& own = result.needles[i].puncture) {
      pre.puncture = *own;  // its depth is the needle's own
      pre.puncture->depth = std::min(own->depth, pre.curve.depth.back());
    }
  } else if (result.puncture && result.puncture->depth - offset > 0) {
    pre.puncture = *result.puncture;
    pre.puncture->depth = std::min(result.puncture->depth - offset, pre.curve.depth.back());
  }
  return pre;
}

}  // namespace

std::string_view to_string(CompleteInsertionStatus status) { return name_of(kCompleteInsertionStatusNames, status); }

CompleteInsertionResult complete_insertion(const IndentationCase& indentation_case,
                                           const CompleteInsertionOptions& options) {
  validate(indentation_case);
  CompleteInsertionResult result;

  // The post-puncture load first: a bad needle mesh or measured curve fails before the FE runs.
  TriangleClassificationOptions classification = options.classification;
  if (classification.bore_radius == 0 && indentation_case.geometry)
    classification.bore_radius = 0.5 * indentation_case.geometry->bore_diameter;
  const geometry::SurfaceMesh surface(indentation_case.needle);
  result.loads = post_puncture_loads(indentation_case.needle, classification, options.post_puncture, &surface);
  result.stiffness = options.model.stiffness;
  result.scale = options.model.scale;
  if (options.measured) {
    result.fit = fit_post_puncture(result.loads, *options.measured, options.model);
    result.stiffness = result.fit->stiffness;
    result.scale = result.fit->scale;
  }

  // The pre-puncture part: the FE (or the given curve), one curve per needle from its own first contact.
  const std::size_t count = indentation_case.needles.size();
  double lowest = indentation_case.needles.front().tip_height;
  for (const NeedleSite& site : indentation_case.needles) lowest = std::min(lowest, site.tip_height);
  std::vector<NeedleInsertion> needles(count);
  for (std::size_t i = 0; i < count; ++i) {
    needles[i].loads = &result.loads;
    needles[i].stiffness = result.stiffness;
    needles[i].scale = result.scale;
    needles[i].contact_offset = indentation_case.needles[i].tip_height - lowest;
  }
  if (options.pre_puncture) {
    for (NeedleInsertion& needle : needles) needle.pre_puncture = *options.pre_puncture;
  } else {
    result.indentation = run_indentation(indentation_case, options.indentation);
    const IndentationResult& fe = *result.indentation;
    if (fe.steps.empty()) {
      result.status = CompleteInsertionStatus::SolverFailed;
      result.reason = fmt::format("the FE indentation converged no load step ({})", fe.reason);
      return result;
    }
    for (std::size_t i = 0; i < count; ++i) {
      needles[i].pre_puncture = needle_pre_puncture_curve(fe, i, needles[i].contact_offset);
      if (needles[i].pre_puncture.curve.depth.size() == 1) {  // never touched within the run: zero to its depth
        needles[i].pre_puncture.curve.depth.push_back(std::max(fe.steps.back().depth, 1e-9));
        needles[i].pre_puncture.curve.force.push_back(0);
      }
    }
  }

  result.curve = insertion_curve(needles, options.curve);
  if (result.indentation && result.indentation->status == IndentationStatus::SolverFailed) {
    result.status = CompleteInsertionStatus::SolverFailed;
    result.reason = fmt::format("the FE indentation stopped: {}; {}", result.indentation->reason, result.curve.reason);
  } else if (result.curve.status == InsertionStatus::NoPuncture) {
    result.status = CompleteInsertionStatus::NoPuncture;
    result.reason = result.curve.reason;
  } else {
    result.status = CompleteInsertionStatus::Complete;
    result.reason = result.curve.reason;
  }
  return result;
}

}  // namespace needlekit::insertion
