// Insertion case files (TOML) for `needlekit insert`: an indentation case file (io/indentation_case.hpp: [needle],
// [[needles]], [tissue], [mesh], [loading], [model], [puncture]) plus
//
//   [post_puncture]                     the cutting phase (insertion/post_puncture_force.hpp)
//   stiffness = "0.84 N/mm2"           K, required: a pressure (N/mm2 = MPa, kPa, Pa), > 0
//   scale = 0.168                       S, required: a number > 0
//   final_depth = "1000 um"             required: the displacement at the end of the curve, > 0
//   samples = 200                       cutting samples from the puncture to final_depth, >= 1
//   reference_radius = "115 um"         R of the β load (default: the needle's largest distance from the axis)
//   max_edge_fraction = 0.025           [0, 1]: bisect loaded triangles longer than this fraction of the needle
//   cap_at_cutting_pressure = true      axial_component = false
//   side_tolerance = "1 deg"            alpha_tolerance = "1 deg"      occlusion_test = false
//   measured = "curve.csv"              optional: a measured post-puncture curve (depth_<unit>, force_<unit>; depth =
//                                       inserted depth of the tip) to fit S to (least squares) and compare with
//
//   [pre_puncture]                      optional: use this pre-puncture curve instead of running the FE
//   curve = "pre.csv"                   depth_<unit>, force_<unit> from first contact; relative to the case file
//   punctured = true                    the last sample is the puncture point (false: no puncture within it)
//
// Errors name FILE:LINE and the key, as the other readers.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "needlekit/insertion/complete_insertion.hpp"
#include "needlekit/insertion/force_curve.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/insertion_curve_parameters.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/insertion/post_puncture_parameters.hpp"
#include "needlekit/insertion/triangle_classification.hpp"
#include "needlekit/insertion/triangle_classification_parameters.hpp"

namespace needlekit::io {

// The parameter tables [post_puncture] is read from, in the order its keys are listed: calls visit(table, member)
// with the matching member of `holder`, an InsertionSettings or an insertion::CompleteInsertionOptions (both name
// them model, curve, post_puncture, classification). The reader, `insert --help` and the JSON echo of the inputs
// go through it, so a new table is added here once.
template <class Holder, class Visit>
void for_each_post_puncture_table(Holder& holder, Visit&& visit) {
  visit(insertion::kPostPunctureFitParameters, holder.model);
  visit(insertion::kInsertionCurveParameters, holder.curve);
  visit(insertion::kPostPunctureParameters, holder.post_puncture);
  visit(insertion::kTriangleClassificationParameters, holder.classification);
}

struct InsertionSettings {
  insertion::PostPunctureFitOptions model;    // K and S (stiffness, scale)
  insertion::InsertionCurveOptions curve;     // final_depth, samples
  insertion::PostPunctureOptions post_puncture;
  insertion::TriangleClassificationOptions classification;
  std::optional<std::filesystem::path> measured;          // resolved against the case file's directory
  std::optional<insertion::PrePunctureCurve> pre_puncture;  // from [pre_puncture]
  // [needle] mesh, resolved against the case file's directory, when the needle is a mesh file (the indentation
  // reader turns an inward-oriented mesh outward silently; `insert` reports it instead).
  std::optional<std::filesystem::path> needle_mesh;
  // The case file with [post_puncture] and [pre_puncture] blanked out (line numbers kept), for the indentation
  // case reader.
  std::string indentation_text;
};

// Throws IoError (TOML syntax, unreadable CSV) or InvalidInput (a missing, unknown or invalid key; a bad CSV).
InsertionSettings parse_insertion_settings(std::string_view text, std::string_view source_name,
                                           const std::filesystem::path& base_directory = ".");

// A whole insertion case file, ready for insertion::complete_insertion: the indentation case, and the options from
// [post_puncture] and [pre_puncture] with the measured curve read.
struct InsertionCase {
  insertion::IndentationCase indentation;
  insertion::CompleteInsertionOptions options;
  std::optional<std::filesystem::path> measured;  // the file options.measured was read from
};

// Reads the file (paths in it relative to its folder). A [needle] mesh must be closed and outward-oriented (the
// indentation reader would turn an inward one silently). Throws IoError or InvalidInput naming FILE:LINE and the key.
InsertionCase read_insertion_case(const std::filesystem::path& path);

}  // namespace needlekit::io
