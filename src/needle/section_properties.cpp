#include "needlekit/needle/section_properties.hpp"

#include <algorithm>
#include <cmath>

namespace needlekit::needle {

ClippedDiskMoments clipped_disk_moments(double R, double t) {
  ClippedDiskMoments m;
  if (R <= 0 || t <= -R) return m;
  const double full_area = M_PI * R * R, full_second = M_PI * R * R * R * R / 4;
  if (t >= R) {
    m.area = full_area;
    m.second_xx = m.second_yy = full_second;
    m.max_x = R;
    return m;
  }
  // Moments of the removed segment x >= t, then subtract from the full disk.
  const double root = std::sqrt(R * R - t * t);
  const double as = std::asin(t / R);
  const double seg_area = R * R * std::acos(t / R) - t * root;
  const double seg_first = 2.0 / 3.0 * root * root * root;  // ∫_t^R 2x√(R²−x²) dx
  // ∫ x²√(R²−x²) dx = x(2x²−R²)√(R²−x²)/8 + R⁴ asin(x/R)/8
  const double seg_xx = 2 * (R * R * R * R * M_PI / 16 - (t * (2 * t * t - R * R) * root / 8 + R * R * R * R * as / 8));
  // ∫ (2/3)(R²−x²)^{3/2} dx with ∫ (R²−x²)^{3/2} dx = x(5R²−2x²)√(R²−x²)/8 + 3R⁴ asin(x/R)/8
  const double seg_yy = 2.0 / 3.0 * (3 * R * R * R * R * M_PI / 16 - (t * (5 * R * R - 2 * t * t) * root / 8 + 3 * R * R * R * R * as / 8));
  m.area = full_area - seg_area;
  m.first_x = -seg_first;
  m.second_xx = full_second - seg_xx;
  m.second_yy = full_second - seg_yy;
  m.max_x = t;
  return m;
}

SectionProperties section_at(const NeedleGeometry& n, double s) {
  s = std::clamp(s, 0.0, n.length);
  const double outer_r = outer_diameter_at(n, s) / 2;
  const double bore_r = n.bore_diameter / 2;
  // The bevel plane keeps x <= x_cut(s) = r − c + c·s/L (header of needle_geometry.hpp); other shapes keep all.
  const double x_cut = n.shape == Shape::Bevel
                           ? outer_r - (n.base_diameter - n.tip_diameter) * (1 - s / n.length)
                           : outer_r;
  const ClippedDiskMoments outer = clipped_disk_moments(outer_r, x_cut);
  const ClippedDiskMoments bore = clipped_disk_moments(bore_r, x_cut);

  SectionProperties p;
  p.area = outer.area - bore.area;
  if (p.area <= 0) return p;
  const double first = outer.first_x - bore.first_x;
  p.centroid_offset = first / p.area;
  const double i_about_y = outer.second_xx - bore.second_xx - p.area * p.centroid_offset * p.centroid_offset;
  const double i_about_x = outer.second_yy - bore.second_yy;
  p.second_moment_min = std::min(i_about_y, i_about_x);
  p.second_moment_max = std::max(i_about_y, i_about_x);
  // Extreme fibres: in x from the centroid to the rim (−R) or to the cut (x_cut); in y the half-height of the region.
  const double fibre_x = std::max(outer.max_x - p.centroid_offset, p.centroid_offset + outer_r);
  const double fibre_y = x_cut >= 0 ? outer_r : std::sqrt(std::max(0.0, outer_r * outer_r - x_cut * x_cut));
  p.section_modulus_min = std::min(i_about_y / fibre_x, i_about_x / fibre_y);
  return p;
}

}  // namespace needlekit::needle
