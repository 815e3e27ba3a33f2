// Per-needle outputs of an indentation run (insertion::NeedleOutcome, ArrayOutcome): the JSON entries of
// "needles" and "array", the per-needle CSV table and a ParaView point set of the needles.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/vtu_writer.hpp"

namespace needlekit::io {

// One entry per needle of the case (of the whole array): "x_um", "y_um", "tip_height_um", and when the result has
// its per-needle record "force_N" and "depth_um" (per step), "punctured", "puncture_step" (null when not),
// "puncture_depth_um", "puncture_force_N" (null when not), "inserted_depth_um".
nlohmann::json needles_json(const insertion::IndentationCase& indentation_case,
                            const insertion::IndentationResult& result);

// For a needle array (null otherwise): "layout", "rows", "columns", "pitch_um", "symmetry", "backing_plate",
// "needles", "plate_travel_um" and "plate_force_N" (per step: the plate's force-displacement), "punctured_fraction"
// (per step), "first_puncture_travel_um" (null when none), "mean_inserted_depth_um", "inserted_depth_spread_um"
// (standard deviation), "mean_penetrated_fraction" (of the needle's length).
nlohmann::json array_json(const insertion::IndentationCase& indentation_case,
                          const insertion::IndentationResult& result);

// needle,row,column,x_um,y_um,punctured,puncture_step,puncture_depth_um,puncture_force_N,final_depth_um,
// final_force_N,inserted_depth_um — one row per needle (row and column empty without an array; the puncture
// columns empty when it did not puncture).
std::string needles_csv(const insertion::IndentationCase& indentation_case, const insertion::IndentationResult& result);

// The needles' tips on the undeformed surface (z = 0) as vertices, with the point fields final_force_N,
// final_depth_um, punctured (0 or 1), puncture_step (0: not punctured) and inserted_depth_um.
VtuGrid needle_map_grid(const insertion::IndentationResult& result);

}  // namespace needlekit::io
