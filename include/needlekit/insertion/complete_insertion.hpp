// The complete insertion of a needle or an array (dissertation §3.4-3.6, Fig 3.11, §6.2 Fig 6.9) as one pipeline:
// the post-puncture load of the needle's mesh (§3.6.2), optionally K·S fitted to a measured post-puncture curve,
// the FE indentation to the puncture point (§3.4-3.5; or a given pre-puncture curve), each needle's pre-puncture
// curve from its own first contact, and the force curve to the final depth (insertion_curve.hpp). `needlekit
// insert`, `needlekit reproduce` (§6.2) and the Python module call this and only present the result.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/insertion/force_curve.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/insertion_curve.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/insertion/triangle_classification.hpp"

namespace needlekit::insertion {

struct CompleteInsertionOptions {
  // K and S of Eq 3.18. With `measured`, the one that fit_stiffness names (S by default) is fitted and the fitted
  // pair is used for the curve.
  PostPunctureFitOptions model;
  // A measured post-puncture curve (depth = inserted depth of the tip, m; force, N) to fit the model to.
  std::optional<ForceDepthCurve> measured;
  PostPunctureOptions post_puncture;             // the β load (reference radius, cap, mesh refinement)
  // The triangle classes. A bore_radius of 0 is taken from the case's parametric needle (half its bore diameter).
  TriangleClassificationOptions classification;
  InsertionCurveOptions curve;                   // final depth and cutting samples
  // Given: every needle uses this pre-puncture curve (depth from its own first contact) and no FE runs.
  std::optional<PrePunctureCurve> pre_puncture;
  IndentationOptions indentation;                // the FE run's progress and per-step callbacks
};

enum class CompleteInsertionStatus {
  Complete,      // the curve reaches the final depth
  NoPuncture,    // a needle did not puncture within its pre-puncture curve: the curve stops at its end
  SolverFailed,  // the FE indentation did not converge a load step: the curve holds the steps that did (if any)
};
inline constexpr EnumTable<CompleteInsertionStatus, 3> kCompleteInsertionStatusNames{{
    {CompleteInsertionStatus::Complete, "complete", "the curve reaches the final depth"},
    {CompleteInsertionStatus::NoPuncture, "no-puncture",
     "a needle did not puncture within its pre-puncture curve: the curve stops there"},
    {CompleteInsertionStatus::SolverFailed, "solver-failed",
     "the FE indentation did not converge a load step: the curve holds the steps that did"},
}};
std::string_view to_string(CompleteInsertionStatus status);  // "complete" | "no-puncture" | "solver-failed"

struct CompleteInsertionResult {
  CompleteInsertionStatus status = CompleteInsertionStatus::Complete;
  std::string reason;                        // always set
  std::optional<IndentationResult> indentation;  // the FE run; empty when options.pre_puncture was given
  PostPunctureLoads loads;                   // the needle's post-puncture load
  std::optional<PostPunctureFit> fit;        // with options.measured
  double stiffness = 0;                      // N/m², K used for the curve (fitted or options.model's)
  double scale = 0;                          // S used for the curve (fitted or options.model's)
  InsertionCurve curve;                      // empty when the FE converged no load step
};

// Runs the pipeline on the case (its needles, tissue, loading and puncture criteria; stop_at_puncture as given).
// Throws InvalidInput for an invalid case, needle mesh, options or measured curve; numerical failure is a status.
CompleteInsertionResult complete_insertion(const IndentationCase& indentation_case,
                                           const CompleteInsertionOptions& options = {});

}  // namespace needlekit::insertion
