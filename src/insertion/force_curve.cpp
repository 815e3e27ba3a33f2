#include "needlekit/insertion/force_curve.hpp"

namespace needlekit::insertion {

std::string_view to_string(PunctureCriterion criterion) { return name_of(kPunctureCriterionNames, criterion); }

}  // namespace needlekit::insertion
