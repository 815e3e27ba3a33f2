// The force-depth curve of a needle insertion and its puncture point: the hand-over between the pre-puncture FE
// indentation (§3.4-3.5) and the post-puncture force model (§3.6). SI units (m, N).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::insertion {

// Which criterion fired: the dissertation's two (puncture_criteria.hpp) or the averaged contact pressure
// (averaged_contact_pressure.hpp).
enum class PunctureCriterion { None, CriticalPressure, FractureEnergy, AveragedPressure };
inline constexpr EnumTable<PunctureCriterion, 4> kPunctureCriterionNames{{
    {PunctureCriterion::None, "none", "no puncture criterion"},
    {PunctureCriterion::CriticalPressure, "critical-pressure",
     "the contact pressure under the tip reaches P_c (Eq 3.17)"},
    {PunctureCriterion::FractureEnergy, "fracture-energy",
     "the released strain energy reaches the fracture energy G_c"},
    {PunctureCriterion::AveragedPressure, "averaged-pressure",
     "the contact pressure averaged over a disc of the material length reaches p_c (Taylor 2007)"},
}};
std::string_view to_string(PunctureCriterion criterion);

struct PuncturePoint {
  double depth = 0;   // m, needle tip displacement below the undeformed surface at puncture
  double force = 0;   // N, reaction force on the needle at puncture
  PunctureCriterion criterion = PunctureCriterion::None;
};

// Samples of (depth, force); depth strictly increasing.
struct ForceDepthCurve {
  std::vector<double> depth;  // m
  std::vector<double> force;  // N
};

// A pre-puncture indentation outcome as the post-puncture model consumes it.
struct PrePunctureCurve {
  ForceDepthCurve curve;
  std::optional<PuncturePoint> puncture;  // empty: no puncture within the simulated depth
};

}  // namespace needlekit::insertion
