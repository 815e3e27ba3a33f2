// Cross-section properties of a needle along its length: what the buckling and bending analyses need.
#pragma once
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::needle {

struct SectionProperties {
  double area = 0;                // m², material area (bore removed)
  double centroid_offset = 0;     // m, x of the centroid (non-zero only for the bevel's asymmetric section)
  double second_moment_min = 0;   // m⁴, smaller principal second moment of area about the centroid
  double second_moment_max = 0;   // m⁴, larger principal second moment
  double section_modulus_min = 0; // m³, smallest I / (distance from the bending axis to the extreme fibre)
};

// Section of the needle at distance s ∈ [0, L] from its tip.
SectionProperties section_at(const NeedleGeometry& needle, double distance_from_tip);

// Moments of the part x <= x_cut of a disk of radius R centred at the origin (a disk clipped by a half-plane).
// Building block of the bevel section, exposed for testing against numerical integration.
struct ClippedDiskMoments {
  double area = 0;       // ∫ dA
  double first_x = 0;    // ∫ x dA
  double second_xx = 0;  // ∫ x² dA (about the disk centre)
  double second_yy = 0;  // ∫ y² dA
  double max_x = 0;      // largest x in the region (x_cut or R)
};
ClippedDiskMoments clipped_disk_moments(double radius, double x_cut);

}  // namespace needlekit::needle
