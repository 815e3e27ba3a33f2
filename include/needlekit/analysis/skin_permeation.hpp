// Skin permeation quantities of one needle (dissertation §4.4–4.7): embedded volume (Table 4.2), hole and annular
// gap volumes (Eqs 4.20–4.22), the geometry factor Q (Table 4.4), the fractional skin volume (Table 4.3) and the
// ideal permeation depth H (Eq 4.23).
#pragma once
#include <string_view>

#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::analysis {

// Diameter of a cone at the skin surface when its tip is at depth h: b = D1 + (D2 − D1)·h/L (§4.5, notes). For a
// bevel, the outer diameter D2; for a cylinder D1.
double diameter_at_skin_surface(const needle::NeedleGeometry& needle, double cutting_depth);

// Table 4.2: volume of the part of the needle inside the skin when the tip is at depth h (0 <= h <= L). The outer
// shape only: the bore is not subtracted (notes: Q is not reduced by the bore). Bevel:
//   V = π/4·h·D2² − (Vol_LW − Vol_SW), Vol_LW = Eq 4.18, Vol_SW = Eq 4.19 (both from Eq 4.17).
double embedded_volume(const needle::NeedleGeometry& needle, double cutting_depth);

// Table 4.4: Q = embedded volume / h (m²). Q(h → 0) is the tip area.
double permeation_factor(const needle::NeedleGeometry& needle, double cutting_depth);

// Eqs 4.20–4.22: the hole is the embedded shape scaled by (1 + δ) in every direction: V_hole = (1 + δ)³·V_embedded.
double hole_volume(const needle::NeedleGeometry& needle, double cutting_depth, double gap_ratio);
// The annular gap: hole volume minus embedded volume (§4.6).
double gap_volume(const needle::NeedleGeometry& needle, double cutting_depth, double gap_ratio);

// Table 4.3 (with the corrected Eq 4.10: skin volume per needle = Pxy²·L_h, L_h = (1 + δ)·h):
//   f_v = (δ³ + 3δ² + 3δ)/(1 + δ) · Q / Pxy².
double fractional_skin_volume(const needle::NeedleGeometry& needle, double cutting_depth, double gap_ratio,
                              double pitch);

// Eq 4.23: H = T for a solid needle, L − d for a hollow needle, when L >= d + T; 0 otherwise.
double ideal_permeation_depth(bool hollow, double length, double deformation, double target_depth);

// Application presets for the target depth T (§4.7): transdermal 50 µm (epidermis–dermis interface); aesthetic
// (tattoo) 1.5 mm (the middle of the 1–2 mm of §4.7); brain 1 mm (cortical probing depth, §5.4).
double application_target_depth(std::string_view application, std::string_view what = "insertion.application");

}  // namespace needlekit::analysis
