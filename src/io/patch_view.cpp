#include "needlekit/io/patch_view.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "needlekit/io/view_arrays.hpp"

namespace needlekit::io {
namespace {

void append(std::vector<float>& out, const Eigen::Vector3d& p) {
  out.insert(out.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
}

// Capacity over demand (> 1: safe); null when there is no demand or no capacity known.
nlohmann::json margin(double capacity, double demand) {
  if (!(demand > 0) || !(capacity > 0)) return nullptr;
  return capacity / demand;
}

nlohmann::json surface_json(const geometry::SurfaceMesh& surface, const Eigen::Vector3d& center, double radius) {
  const geometry::TriangleMesh& mesh = surface.mesh();
  std::vector<int> vertex_of(mesh.vertices.size(), -1);
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  for (const auto& t : mesh.triangles) {
    bool near = false;
    for (int k : t) near = near || (mesh.vertices[k] - center).norm() < radius;
    if (!near) continue;
    for (int k : t) {
      if (vertex_of[k] < 0) {
        vertex_of[k] = static_cast<int>(positions.size() / 3);
        append(positions, mesh.vertices[k]);
      }
      indices.push_back(static_cast<std::uint32_t>(vertex_of[k]));
    }
  }
  return {{"region", "near the patch"},
          {"vertices", positions.size() / 3},
          {"triangles", indices.size() / 3},
          {"indices", uint32_array(indices)},
          {"positions", float32_array(positions)},
          {"fields", nlohmann::json::array()}};
}

}  // namespace

nlohmann::json patch_view(const std::string& name, const geometry::SurfaceMesh& surface,
                          const patch::PatchDesign& design, const patch::FittedPatch& fit,
                          const patch::PatchEvaluation& evaluation) {
  const double diagonal = std::hypot(design.width_u, design.width_v);
  std::vector<float> lines, segments;
  for (const patch::Spring& spring : design.springs) {
    append(lines, fit.positions[spring.a]);
    append(lines, fit.positions[spring.b]);
  }
  const double buckling_capacity = evaluation.reference.buckling.critical_load;
  const std::optional<double>& bending_capacity = evaluation.reference.critical_bending_load;
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t n = 0; n < evaluation.needles.size(); ++n) {
    const patch::NeedleState& s = evaluation.needles[n];
    append(segments, s.base);
    append(segments, s.tip);
    rows.push_back({n, design.column(static_cast<int>(n)), design.row(static_cast<int>(n)), s.buckling_force,
                    s.bending_force, margin(buckling_capacity, s.buckling_force),
                    bending_capacity ? margin(*bending_capacity, s.bending_force) : nlohmann::json(nullptr),
                    s.angle * 180 / M_PI, s.penetration * 1e6, s.performance_index * 1e-6, s.status});
  }
  const auto column = [](const char* key, const char* label, const char* unit, bool colour) {
    return nlohmann::json{{"key", key}, {"label", label}, {"unit", unit}, {"colour", colour}};
  };
  nlohmann::json columns = nlohmann::json::array(
      {column("node", "node", "", false), column("i", "i", "", false), column("j", "j", "", false),
       column("buckling_force_N", "buckling force |F|/cos(theta)", "N", true),
       column("bending_force_N", "bending force |F| tan(theta)", "N", true),
       column("buckling_margin", "buckling margin P_cr / force", "", true),
       column("bending_margin", "bending margin P_Be / force", "", true), column("angle_deg", "angle", "deg", true),
       column("penetration_um", "penetration x - d", "um", true),
       column("performance_index_per_um", "performance index", "1/um", true), column("status", "status", "", false)});
  nlohmann::json view = {{"format", "needlekit-view/1"}, {"kind", "patch"}, {"name", name}};
  view["title"] = fmt::format("{}: {} x {} needles fitted ({}), {} penetrate", name, design.nodes_u, design.nodes_v,
                              patch::to_string(fit.status), evaluation.penetrating);
  view["steps"] = nlohmann::json::array({{{"label", "fitted patch"}}});
  view["steps_total"] = 1;
  view["surface"] = surface_json(surface, fit.frame.surface_point, diagonal);
  view["lines"] = {{"positions", float32_array(lines)}};
  view["needles"] = {{"segments", float32_array(segments)},
                     {"radius_m", 0.5 * design.needle.base_diameter},
                     {"table", {{"columns", columns}, {"rows", rows}}}};
  view["notes"] = nlohmann::json::array();
  return view;
}

}  // namespace needlekit::io
