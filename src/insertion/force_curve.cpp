#include "needlekit/insertion/force_curve.hpp"

namespace needlekit::insertion {

std::string to_string(PunctureCriterion criterion) {
  switch (criterion) {
    case PunctureCriterion::CriticalPressure: return "critical-pressure";
    case PunctureCriterion::FractureEnergy: return "fracture-energy";
    case PunctureCriterion::AveragedPressure: return "averaged-pressure";
    case PunctureCriterion::None: break;
  }
  return "none";
}

}  // namespace needlekit::insertion
