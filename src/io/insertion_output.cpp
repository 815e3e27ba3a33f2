#include "needlekit/io/insertion_output.hpp"

#include <fmt/format.h>

namespace needlekit::io {
namespace {

// The marker of each sample: "puncture" before a relaxation drop, "relaxed" after it.
std::vector<std::string> markers(const insertion::InsertionCurve& curve) {
  std::vector<std::string> marker(curve.depth.size());
  for (std::size_t s = 0; s + 1 < curve.depth.size(); ++s)
    if (curve.depth[s] == curve.depth[s + 1] && curve.punctured_needles[s + 1] > curve.punctured_needles[s]) {
      marker[s] = "puncture";
      marker[s + 1] = "relaxed";
    }
  return marker;
}

}  // namespace

std::string insertion_curve_csv(const insertion::InsertionCurve& curve) {
  const auto marker = markers(curve);
  // An array's (more than one needle's) curve adds each needle's force as a column.
  const std::size_t columns = curve.needle_force.size() > 1 ? curve.needle_force.size() : 0;
  std::string csv = "depth_um,force_N,phase,punctured_needles,marker";
  for (std::size_t i = 0; i < columns; ++i) csv += fmt::format(",needle_{}_force_N", i + 1);
  csv += '\n';
  for (std::size_t s = 0; s < curve.depth.size(); ++s) {
    csv += fmt::format("{:.9g},{:.9g},{},{},{}", curve.depth[s] * 1e6, curve.force[s], to_string(curve.phase[s]),
                       curve.punctured_needles[s], marker[s]);
    for (std::size_t i = 0; i < columns; ++i) csv += fmt::format(",{:.9g}", curve.needle_force[i][s]);
    csv += '\n';
  }
  return csv;
}

nlohmann::json insertion_curve_json(const insertion::InsertionCurve& curve) {
  nlohmann::json json;
  json["status"] = to_string(curve.status);
  json["reason"] = curve.reason;
  std::vector<double> depth_um(curve.depth.size());
  std::vector<std::string> phase(curve.depth.size());
  for (std::size_t s = 0; s < curve.depth.size(); ++s) {
    depth_um[s] = curve.depth[s] * 1e6;
    phase[s] = to_string(curve.phase[s]);
  }
  json["depth_um"] = depth_um;
  json["force_N"] = curve.force;
  json["phase"] = phase;
  json["punctured_needles"] = curve.punctured_needles;
  json["marker"] = markers(curve);
  json["puncture_depth_um"] = nullptr;
  json["puncture_force_N"] = nullptr;
  json["relaxation_drop_N"] = nullptr;
  nlohmann::json punctures = nlohmann::json::array();
  for (const auto& event : curve.punctures)
    punctures.push_back({{"needle", event.needle + 1},
                         {"displacement_um", event.displacement * 1e6},
                         {"depth_um", event.depth * 1e6},
                         {"force_before_N", event.force_before},
                         {"force_after_N", event.force_after},
                         {"drop_N", event.drop}});
  json["punctures"] = punctures;
  if (!curve.punctures.empty()) {
    // The first puncture of the array: the total force just before and just after it.
    const double u = curve.punctures.front().displacement;
    for (std::size_t s = 0; s + 1 < curve.depth.size(); ++s)
      if (curve.depth[s] == u && curve.depth[s + 1] == u) {
        json["puncture_depth_um"] = u * 1e6;
        json["puncture_force_N"] = curve.force[s];
        json["relaxation_drop_N"] = curve.force[s] - curve.force[s + 1];
        break;
      }
  }
  return json;
}

}  // namespace needlekit::io
