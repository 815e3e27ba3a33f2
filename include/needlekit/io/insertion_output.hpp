// Outputs of a complete insertion (insertion/insertion_curve.hpp): the curve as CSV and JSON with the phase of every
// sample and markers at the puncture points, in the units named by the columns and keys (um, N).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/insertion/insertion_curve.hpp"

namespace needlekit::io {

// depth_um,force_N,phase,punctured_needles,marker — one row per sample; phase is "indentation" or "cutting"; marker
// is "puncture" on the last indentation sample of a puncture, "relaxed" on the sample just after its drop, else empty.
std::string insertion_curve_csv(const insertion::InsertionCurve& curve);

// {"status", "reason", "depth_um", "force_N", "phase", "punctured_needles" (arrays, one entry per sample),
//  "puncture_depth_um", "puncture_force_N", "relaxation_drop_N" (the first puncture; null if none),
//  "punctures": [{"needle", "displacement_um", "depth_um", "force_before_N", "force_after_N", "drop_N"}]}.
nlohmann::json insertion_curve_json(const insertion::InsertionCurve& curve);

}  // namespace needlekit::io
