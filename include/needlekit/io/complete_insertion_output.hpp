// The result JSON of a complete insertion (insertion/complete_insertion.hpp), as `needlekit insert --json` prints it
// and NAME_insertion.json holds: the curve (io/insertion_output.hpp) with the run's status, the post-puncture model's
// K and S (fitted or the case's), the FE run's summary and the needle's triangle classification (§3.6). Units in the
// keys.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "needlekit/insertion/complete_insertion.hpp"
#include "needlekit/io/insertion_case.hpp"

namespace needlekit::io {

// insertion_curve_json(result.curve) plus "status", "reason", "name", "needles" (count), "stiffness_N_per_mm2",
// "scale", "scale_source" ("fitted" | "case"), "case_scale", "final_depth_um", "pre_puncture_source" ("fe" | "csv"),
// "complete" (false: the curve stops where the FE failed), "notes" (the scale warnings given), "fe" ({"status",
// "reason", "elements", "nodes", "total_seconds", "models"}; absent for a measured pre-puncture curve),
// "classification" (triangle counts and areas), "fit" (null unless S was fitted to a measured curve) and "inputs"
// (indentation_inputs_json plus the rows of [post_puncture]'s four tables: model, curve, beta load, classification).
nlohmann::json complete_insertion_json(const InsertionCase& insertion_case,
                                       const insertion::CompleteInsertionResult& result,
                                       const std::vector<std::string>& notes);

}  // namespace needlekit::io
