// The complete insertion force curve (dissertation §3.5-3.6, Fig 3.11, §6.2 Fig 6.9): the pre-puncture curve of each
// needle up to its puncture point, then the post-puncture (cutting) force of insertion/post_puncture_force.hpp, for
// one needle or an array. An array's force is the sum over its needles: each needle contributes its indentation force
// until it punctures and its cutting force afterwards, so the post-puncture load comes only from needles that have
// punctured.
//
// At the puncture point the tissue relaxes (§6.2: "the drop in force resistance after microneedle insertion could be
// due to the relaxation of tissue phantom"): the force jumps from the pre-puncture force to the cutting force at the
// same depth. The curve carries both samples at that depth and reports the drop.
//
// Depth convention: the needle's displacement since its tip touched the undeformed surface (= the inserted depth of
// the tip once the tissue has relaxed after puncture).
#pragma once
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/insertion/force_curve.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"

namespace needlekit::insertion {

enum class InsertionPhase { Indentation, Cutting };
inline constexpr EnumTable<InsertionPhase, 2> kInsertionPhaseNames{{
    {InsertionPhase::Indentation, "indentation", "before puncture: the tissue is indented"},
    {InsertionPhase::Cutting, "cutting", "after puncture: the needle cuts into the tissue"},
}};
std::string_view to_string(InsertionPhase phase);  // "indentation" | "cutting"

// One needle of the insertion.
struct NeedleInsertion {
  PrePunctureCurve pre_puncture;          // this needle's curve (depth from its own first contact)
  const PostPunctureLoads* loads = nullptr;  // its post-puncture load (not owned; may be shared between needles)
  double stiffness = 0.2e6;               // N/m², > 0: K of Eq 3.18
  double scale = 0.168;                   // > 0: S of Eq 3.18 (§6.2: 0.168, sharp bevel in silicone rubber)
  double contact_offset = 0;              // m, >= 0: displacement of the array at which this needle's tip touches
};

struct InsertionCurveOptions {
  double final_depth = 1e-3;              // m, > 0: displacement of the array at the end of the curve
  int cutting_samples = 200;              // >= 1: equally spaced samples from the first puncture to final_depth
};

enum class InsertionStatus {
  Complete,            // the curve reaches final_depth
  NoPuncture,          // some needle has not punctured by the end of its pre-puncture curve, which ends before
                       // final_depth: the curve stops there
};
inline constexpr EnumTable<InsertionStatus, 2> kInsertionStatusNames{{
    {InsertionStatus::Complete, "complete", "the curve reaches final_depth"},
    {InsertionStatus::NoPuncture, "no-puncture",
     "some needle has not punctured by the end of its pre-puncture curve: the curve stops there"},
}};
std::string_view to_string(InsertionStatus status);

struct PunctureEvent {
  int needle = 0;
  double displacement = 0;   // m, of the array when this needle punctured
  double depth = 0;          // m, the needle's own depth at puncture
  double force_before = 0;   // N, this needle's pre-puncture force at the puncture point
  double force_after = 0;    // N, its post-puncture force at the same depth
  double drop = 0;           // N, force_before − force_after (the relaxation drop; negative: the force rises)
};

struct InsertionCurve {
  InsertionStatus status = InsertionStatus::Complete;
  std::string reason;
  std::vector<double> depth;              // m, displacement of the array, non-decreasing (repeated at punctures)
  std::vector<double> force;              // N, total force on the needles
  std::vector<InsertionPhase> phase;      // Cutting once at least one needle has punctured
  std::vector<int> punctured_needles;     // how many needles have punctured at each sample
  std::vector<PunctureEvent> punctures;   // in the order they happen
  // N, per needle (in the order given), per sample: its indentation force until it punctures, its cutting force
  // (Alg 3.1, Eq 3.20) after; their sum over the needles is `force`.
  std::vector<std::vector<double>> needle_force;
};

// Throws InvalidInput naming the field: no needle, missing loads, a pre-puncture curve that does not start at depth
// >= 0 or whose depths are not increasing, a puncture beyond its curve, K, S, offset, final depth or samples out of
// range.
InsertionCurve insertion_curve(const std::vector<NeedleInsertion>& needles, const InsertionCurveOptions& options = {});

}  // namespace needlekit::insertion
