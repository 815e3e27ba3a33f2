// Puncture point determination (dissertation §3.5): the critical-pressure criterion, the fracture-energy criterion
// (Eqs 3.13-3.17) and the fracture toughness J from two insertions at the same spot (Eq 3.16), together the
// `dissertation` law; and the `averaged-pressure` law (averaged_contact_pressure.hpp), which reads the contact field
// and works under true (surface) contact. SI units (m, N, Pa, J, J/m^2).
//
// Both criteria read the per-step state of a pre-puncture indentation (depth, reaction force, contact area, stored
// strain energy) and return the first depth at which they fire, interpolated linearly between the two load steps
// that bracket it (no interpolation below the first sample: a criterion already met at the first sample fires there).
//
// Reading of Eqs 3.13-3.17 (the text leaves dA and dΔ open; see docs/indentation.md):
//  - Eq 3.14, F dx = J dA + dΔ, is the energy balance of one increment. Before puncture no crack exists (dA = 0) and
//    quasi-static loading stores all the work: W = ∫F dx = Δ with Δ = ½uᵀKu the strain energy (checked by the FE
//    verification tests).
//  - dA, the crack area, is the area of the tissue surface in contact with the needle tip (the crack that initiates
//    is the cut of the loaded area under the tip: for a flat punch, its face πa²).
//  - At the instant of cracking the needle does not move (dx = 0), so Eq 3.14 becomes J·A = −dΔ: the crack can form
//    when the strain energy that it releases (at most all of Δ, as the tissue under the tip unloads) pays for its
//    surface. The fracture-energy criterion therefore fires when Δ ≥ J·A (a Griffith-type upper bound).
//  - The pressure of Eq 3.17 is P_s = F/A, the mean pressure under the tip; the critical-pressure criterion fires when
//    P_s ≥ P_c (0.663 MPa for the silicone-rubber phantom of §6.2).
#pragma once
#include <optional>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/insertion/force_curve.hpp"

namespace needlekit::insertion {

// The state after one converged load step, as the criteria read it.
struct PunctureSample {
  double depth = 0;          // m, needle tip displacement below the undeformed surface, strictly increasing
  double force = 0;          // N, reaction force on the needle(s) (positive pushing the tissue down)
  double contact_area = 0;   // m^2, tissue surface area in contact with the tip (dA of Eq 3.17), >= 0
  double strain_energy = 0;  // J, stored strain energy Δ = ½uᵀKu (Eq 3.17), >= 0
  double averaged_pressure = 0;  // Pa, p̄_l of the averaged-pressure law (averaged_peak_pressure), >= 0
};

// Mean contact pressure under the tip, P_s = F/A (Eq 3.17); 0 when nothing touches (A = 0).
double contact_pressure(const PunctureSample& sample);

// Which law decides the puncture ([puncture] criterion).
enum class PunctureLaw {
  Dissertation,      // §3.5: the mean pressure F/A reaches P_c and/or the strain energy reaches J·A
  AveragedPressure,  // the contact pressure averaged over a disc of radius material_length reaches P_c
};
inline constexpr EnumTable<PunctureLaw, 2> kPunctureLawNames{{
    {PunctureLaw::Dissertation, "dissertation",
     "§3.5: mean pressure F/A over the contact area >= critical_pressure, and/or strain energy >= toughness x area"},
    {PunctureLaw::AveragedPressure, "averaged-pressure",
     "contact pressure averaged over a disc of radius material_length, at its highest, >= critical_pressure "
     "(surface contact)"},
}};

struct PunctureOptions {
  PunctureLaw criterion = PunctureLaw::Dissertation;
  std::optional<double> critical_pressure;  // Pa, > 0: P_c of the critical-pressure criterion or of the averaged-
                                            // pressure law; empty: not used
  std::optional<double> toughness;          // J/m^2, > 0: J of the fracture-energy criterion; empty: not used
  double material_length = 50e-6;           // m, > 0: the averaged-pressure law's l (the disc's radius)
};

// Throws InvalidInput naming the field: a given P_c or J that is not finite and positive, a material length outside
// its range, the averaged-pressure law without a critical pressure or with a toughness (a dissertation criterion).
void validate(const PunctureOptions& options);

// The first point where p̄_l reaches P_c (averaged_contact_pressure.hpp), or empty.
std::optional<PuncturePoint> averaged_pressure_puncture(const std::vector<PunctureSample>& samples,
                                                        double critical_pressure);

// The first point where P_s = F/A reaches P_c (Eq 3.17), or empty.
std::optional<PuncturePoint> critical_pressure_puncture(const std::vector<PunctureSample>& samples,
                                                        double critical_pressure);

// The first point where the stored strain energy Δ reaches J·A (Eq 3.14 with dx = 0 at the instant of cracking), or
// empty.
std::optional<PuncturePoint> fracture_energy_puncture(const std::vector<PunctureSample>& samples, double toughness);

// The averaged-pressure law's point, or for the dissertation law the earliest (smallest depth) point of its enabled
// criteria, with the criterion that fired (the critical pressure wins a tie); empty when no criterion fires or none
// is enabled.
std::optional<PuncturePoint> puncture_point(const std::vector<PunctureSample>& samples, const PunctureOptions& options);

struct ToughnessOptions {
  double crack_area = 0;      // m^2, > 0: the crack area dA created by the first insertion (e.g. the tip area)
  double min_depth = 0;       // m, >= 0: start of the integration range (clipped to both curves)
  std::optional<double> max_depth;  // m, > min_depth: end of the range; empty: the end of the shorter curve
};

struct ToughnessResult {
  double toughness = 0;    // J/m^2, J = ∫(F − F') dx / dA (Eq 3.16 over the range)
  double energy = 0;       // J, ∫(F − F') dx: the work spent on the crack
  double min_depth = 0;    // m, the range actually integrated
  double max_depth = 0;    // m
};

// Fracture toughness from two insertions at the same spot (Eq 3.16): the first insertion F(x) cracks the tissue,
// the second F'(x) only deforms it, so their work difference over the range is the crack's energy J·dA. Both curves
// are interpolated linearly; the integral is exact for the piecewise-linear curves. Throws InvalidInput if a curve
// has fewer than two samples or a non-increasing depth, the range is empty, or the crack area is not positive.
ToughnessResult two_insertion_toughness(const ForceDepthCurve& first, const ForceDepthCurve& second,
                                        const ToughnessOptions& options);

}  // namespace needlekit::insertion
