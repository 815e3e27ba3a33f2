#include "needlekit/insertion/averaged_contact_pressure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "needlekit/core/errors.hpp"

namespace needlekit::insertion {

double averaged_peak_pressure(const std::vector<ContactPoint>& points, double material_length) {
  if (!std::isfinite(material_length) || !(material_length > 0)) {
    throw InvalidInput(fmt::format("puncture.material_length: {} m is not positive, expected a length > 0",
                                   material_length));
  }
  const double reach = material_length * material_length;
  double highest = 0;
  // Every contact point as the disc's centre: O(n^2) in the points in contact (a few hundred per needle).
  for (const ContactPoint& centre : points) {
    double force = 0, area = 0;
    for (const ContactPoint& point : points) {
      if ((point.position - centre.position).squaredNorm() <= reach) {
        force += point.force;
        area += point.area;
      }
    }
    if (area > 0) highest = std::max(highest, force / area);  // Taylor 2007's area method, on the contact pressure
  }
  return highest;
}

}  // namespace needlekit::insertion
