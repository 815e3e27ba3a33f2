// Critical bending load of a needle loaded laterally at its tip (dissertation §5.2, Eqs 5.7, 5.8) and the forces of
// an angled insertion (Eqs 5.3, 5.4).
#pragma once
#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::analysis {

// Critical lateral tip load P_Be (N) at which the bending stress reaches the allowable stress σ (Pa):
//   P_Be = σ · min over s ∈ (0, L] of S(s)/s, with S(s) the smallest section modulus at distance s from the tip.
// For solid round sections this is Eq 5.7 (uniform: σπD³/(32L)) and Eq 5.8 (cone with t = D2/D1 >= 1.5:
// 27σ(t−1)πD1³/(128L)); for 1 < t < 1.5 the maximum stress is at the base, σπD2³/(32L) (notes). Hollow and bevel
// sections use the same definition with their actual section modulus (evaluated in closed form where possible,
// otherwise by a scan refined by golden-section search).
double critical_bending_load(const needle::NeedleGeometry& needle, double allowable_stress);

// Eq 5.3 (notes): the force that loads the needle axially in an insertion at angle θ to the surface normal,
// |F|/cos θ.
double angled_buckling_force(double puncture_force, double angle);
// Eq 5.4 (notes): the lateral force that bends the needle, |F|·tan θ.
double angled_bending_force(double puncture_force, double angle);

}  // namespace needlekit::analysis
