// The tissue's resistance to puncture (dissertation §4.2, §5.3): the puncture force as a function of the tip area
// (Eq 4.2) and the tissue deformation before puncture (Eqs 4.1, 4.3), with the small-tip branch of the notes.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/analysis/puncture_force_law.hpp"

namespace needlekit::analysis {

struct PunctureModel {
  std::string name = "skin";
  double alpha = 0.0183;          // N, pre-exponential constant of F(d) = α·e^{τd} (Eq 4.1), > 0
  double tau = 6250.0;            // 1/m, exponential constant τ (6.25 /mm for skin), > 0
  // The puncture force F(A) ([tissue] puncture_force): Eq 4.2 by default (puncture_force_law.hpp).
  PunctureForceLaw force_law = eq_4_2_puncture_force_law();
  // Small-tip branch (notes, "Deformation before puncture"): when F(A) <= α the deformation is d = K·A, a line
  // through the origin with K = 0.0608 µm/µm² = 6.08e4 1/m (= 2·0.00019·1000/τ for skin). Kept for brain too:
  // the text does not say whether K scales with τ.
  double small_tip_slope = 6.08e4;  // 1/m
};

// Presets: skin (α = 0.0183 N, τ = 6.25 /mm) and brain (α = 0.0013 N, τ = 8.5076 /mm), dissertation Tables 6.4/6.5.
PunctureModel skin_puncture_model();
PunctureModel brain_puncture_model();
// The preset names puncture_model_preset() accepts, in a stable order: skin, brain.
std::vector<std::string> puncture_model_preset_names();
// "skin" or "brain"; throws InvalidInput naming `what` otherwise.
PunctureModel puncture_model_preset(std::string_view name, std::string_view what = "tissue.model");
// Throws InvalidInput for non-positive α, τ or K, or an invalid force law.
void validate(const PunctureModel& model, std::string_view where = "tissue");

// The model's force law at tip area A (Eq 4.2 by default: F(A) = 0.00019·A − 0.66, A in µm², F in N), signed.
// Eq 4.2 is negative for A < 3473.7 µm²; the dissertation's figures show |F| (notes).
double puncture_force(double tip_area, const PunctureModel& model);

struct SkinDeformation {
  double depth = 0;            // m, d: needle travel before the skin is punctured
  bool small_tip_branch = false;  // true when d = K·A was used because F(A) <= α
};

// Eq 4.3: d = (1/τ)·ln(F(A)/α) when F(A) > α, else d = K·A (notes).
SkinDeformation skin_deformation(double tip_area, const PunctureModel& model);

// Eq 4.4: cutting depth h = L − d (may be negative: the needle never gets in).
inline double cutting_depth(double length, double deformation) { return length - deformation; }

// The tip area below which the small-tip branch applies (F(A) = α), m².
double small_tip_area_limit(const PunctureModel& model);

}  // namespace needlekit::analysis
