// Volume of a cylindrical wedge (dissertation §4.5, Fig 4.7): the part of a cylinder of radius r cut off by a plane
// through a chord at one end (base width c, measured from the rim) and the opposite rim point at height ℓ.
#pragma once

namespace needlekit::needle {

// Eq 4.17 (with the corrected Eqs 4.12, 4.14, 4.15 of the notes):
//   V = ℓ/(3c)·[a(3r² − a²) + 3r²(c − r)θ],  a = √(2rc − c²),  θ = π/2 + atan((c − r)/a).
// Valid for 0 < c <= 2r; returns 0 for c <= 0. ℓ is the wedge's length along the axis.
double cylindrical_wedge_volume(double radius, double base_width, double wedge_length);

}  // namespace needlekit::needle
