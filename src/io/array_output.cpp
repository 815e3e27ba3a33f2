#include "needlekit/io/array_output.hpp"

#include <fmt/format.h>

#include <sstream>

namespace needlekit::io {
namespace {

nlohmann::json scaled_or_null(bool present, double value, double scale) {
  return present ? nlohmann::json(value * scale) : nlohmann::json(nullptr);
}

std::vector<double> scaled(const std::vector<double>& values, double scale) {
  std::vector<double> out;
  out.reserve(values.size());
  for (double v : values) out.push_back(v * scale);
  return out;
}

}  // namespace

nlohmann::json needles_json(const insertion::IndentationCase& c, const insertion::IndentationResult& result) {
  const bool recorded = result.needles.size() == c.needles.size();
  nlohmann::json needles = nlohmann::json::array();
  for (std::size_t i = 0; i < c.needles.size(); ++i) {
    const insertion::NeedleSite& site = c.needles[i];
    nlohmann::json entry{{"x_um", site.position.x() * 1e6}, {"y_um", site.position.y() * 1e6},
                         {"tip_height_um", site.tip_height * 1e6}};
    if (recorded) {
      const insertion::NeedleOutcome& needle = result.needles[i];
      const bool punctured = needle.puncture.has_value();
      entry["force_N"] = needle.force;
      entry["depth_um"] = scaled(needle.depth, 1e6);
      entry["punctured"] = punctured;
      entry["puncture_step"] = punctured ? nlohmann::json(needle.puncture_step) : nlohmann::json(nullptr);
      entry["puncture_depth_um"] = scaled_or_null(punctured, punctured ? needle.puncture->depth : 0.0, 1e6);
      entry["puncture_force_N"] = scaled_or_null(punctured, punctured ? needle.puncture->force : 0.0, 1.0);
      entry["inserted_depth_um"] = needle.inserted_depth * 1e6;
    }
    needles.push_back(std::move(entry));
  }
  return needles;
}

nlohmann::json array_json(const insertion::IndentationCase& c, const insertion::IndentationResult& result) {
  if (!c.array || !result.array) return nullptr;
  const insertion::NeedleArray& a = *c.array;
  const insertion::ArrayOutcome& outcome = *result.array;
  std::vector<double> plate_force;
  for (const insertion::IndentationStep& step : result.steps) plate_force.push_back(step.force);
  return {{"layout", name_of(insertion::kArrayLayoutNames, a.layout)},
          {"rows", a.rows},
          {"columns", a.columns},
          {"pitch_um", a.pitch * 1e6},
          {"symmetry", name_of(insertion::kArraySymmetryNames, a.symmetry)},
          {"backing_plate", a.backing_plate},
          {"needles", c.needles.size()},
          {"plate_travel_um", scaled(outcome.plate_travel, 1e6)},
          {"plate_force_N", plate_force},
          {"punctured_fraction", outcome.punctured_fraction},
          {"first_puncture_travel_um", scaled_or_null(outcome.first_puncture_travel.has_value(),
                                                      outcome.first_puncture_travel.value_or(0.0), 1e6)},
          {"mean_inserted_depth_um", outcome.mean_inserted_depth * 1e6},
          {"inserted_depth_spread_um", outcome.inserted_depth_spread * 1e6},
          {"mean_penetrated_fraction", outcome.mean_penetrated_fraction}};
}

std::string needles_csv(const insertion::IndentationCase& c, const insertion::IndentationResult& result) {
  std::ostringstream out;
  out << "needle,row,column,x_um,y_um,punctured,puncture_step,puncture_depth_um,puncture_force_N,final_depth_um,"
         "final_force_N,inserted_depth_um\n";
  for (std::size_t i = 0; i < result.needles.size(); ++i) {
    const insertion::NeedleOutcome& n = result.needles[i];
    const std::string row = c.array ? std::to_string(static_cast<int>(i) / c.array->columns) : "";
    const std::string column = c.array ? std::to_string(static_cast<int>(i) % c.array->columns) : "";
    const std::string puncture =
        n.puncture ? fmt::format("1,{},{:.9g},{:.9g}", n.puncture_step, n.puncture->depth * 1e6, n.puncture->force)
                   : std::string("0,,,");
    out << fmt::format("{},{},{},{:.9g},{:.9g},{},{:.9g},{:.9g},{:.9g}\n", i, row, column, n.position.x() * 1e6,
                       n.position.y() * 1e6, puncture, n.depth.empty() ? 0.0 : n.depth.back() * 1e6,
                       n.force.empty() ? 0.0 : n.force.back(), n.inserted_depth * 1e6);
  }
  return out.str();
}

VtuGrid needle_map_grid(const insertion::IndentationResult& result) {
  VtuGrid grid;
  VtuField force{"final_force_N", 1, {}}, depth{"final_depth_um", 1, {}}, punctured{"punctured", 1, {}};
  VtuField step{"puncture_step", 1, {}}, inserted{"inserted_depth_um", 1, {}};
  for (const insertion::NeedleOutcome& n : result.needles) {
    grid.cells.push_back({static_cast<int>(grid.points.size())});
    grid.cell_types.push_back(VtkCellType::Vertex);
    grid.points.emplace_back(n.position.x(), n.position.y(), 0.0);
    force.values.push_back(n.force.empty() ? 0.0 : n.force.back());
    depth.values.push_back(n.depth.empty() ? 0.0 : n.depth.back() * 1e6);
    punctured.values.push_back(n.puncture ? 1.0 : 0.0);
    step.values.push_back(n.puncture_step);
    inserted.values.push_back(n.inserted_depth * 1e6);
  }
  grid.point_fields = {std::move(force), std::move(depth), std::move(punctured), std::move(step), std::move(inserted)};
  return grid;
}

}  // namespace needlekit::io
