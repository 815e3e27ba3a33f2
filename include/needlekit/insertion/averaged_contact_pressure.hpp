// The averaged-pressure puncture law (docs/indentation.md, "Averaged contact pressure"): the tissue punctures when the
// contact pressure averaged over a disc of a material length l, at the disc where that average is highest, reaches a
// critical pressure p_c. SI units (m, N, Pa).
//
// The law is the area method of the Theory of Critical Distances (Taylor, The Theory of Critical Distances, Elsevier
// 2007, ch. 2; the average-stress criterion of Whitney & Nuismer, J. Compos. Mater. 8, 1974, 253–265): a solid with
// a stress concentration fails when the stress averaged over a region of a size l, a property of the material, reaches
// its strength. Under a needle the stress raiser is the contact edge or the tip, and the stress there is the contact
// pressure:
//
//   p̄_l = max over contact points c of  Σ_{|X_i − X_c| <= l} F_i / Σ_{|X_i − X_c| <= l} A_i,   puncture when p̄_l >= p_c,
//
// F_i the axial contact force of tissue node i (along the needle's axis), A_i its tributary area of the undeformed
// surface and X_i its reference position. Unlike Eq 3.17's mean pressure F/A over the whole contact area, p̄_l does
// not fall when tissue wraps round a rim (the wrapped nodes are outside the disc at the rim, or carry no axial force),
// and it converges with the mesh once the elements at the tip are smaller than l (a field's average over a fixed
// disc, also of the integrable square-root singularity at a flat punch's rim).
//
// What the law predicts (dimensional analysis and the closed-form contact fields):
//  - p̄_l/μ depends only on the depth over the tip size R, l/R and the law's constants: runs with the same l/R and
//    p_c/μ puncture at the same depth/R and mean pressure p/μ;
//  - a flat punch of radius a (Sneddon 1965, p = F/(2πa√(a² − r²))): p̄_l ≈ 0.79 p_m √(a/l) for l ≪ a (the half disc
//    at the rim), so it punctures at the mean pressure p_m ≈ 1.27 p_c √(l/a), falling as a grows; at l ≫ a, p̄ = p_m
//    and it punctures at p_c;
//  - a sphere (Hertz, p = p_0 √(1 − r²/a²)): p̄_l → p_0 = 3/2 p_m for l ≪ a and p_m for l ≫ a, so it punctures at a
//    mean contact pressure between 2/3 p_c and p_c, and at a far lower load over its shank's section than a flat punch
//    of the same diameter (Shergold & Fleck, J. Biomech. Eng. 127, 2005, 838–848: blunt punches need higher pressures).
#pragma once
#include <Eigen/Core>
#include <vector>

namespace needlekit::insertion {

// One tissue node in contact with a needle.
struct ContactPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m, reference (undeformed) position
  double force = 0;                                    // N, contact force along the needle's axis (>0 pushing)
  double area = 0;                                     // m^2, >= 0: tributary area of the undeformed surface
};

// Pa: p̄_l, the highest pressure resultant over the area it acts on, of the points within `material_length` (m, > 0)
// of any one point; 0 when there is no point or no area. Throws InvalidInput for a length that is not positive.
double averaged_peak_pressure(const std::vector<ContactPoint>& points, double material_length);

}  // namespace needlekit::insertion
