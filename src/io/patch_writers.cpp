#include "needlekit/io/patch_writers.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace needlekit::io {
namespace {

nlohmann::json stats_json(const patch::Statistics& s, double scale, bool with_total = false) {
  if (s.count == 0) return nullptr;
  nlohmann::json j{{"min", s.min * scale}, {"max", s.max * scale}, {"mean", s.mean * scale}};
  if (with_total) j["total"] = s.total * scale;
  return j;
}

}  // namespace

int failure_code(const patch::NeedleState& s) {
  if (s.status == "short") return 1;
  if (s.status == "buckles") return 2;
  if (s.status == "bends") return 3;
  if (s.status == "no_surface") return 4;
  if (s.status == "too_shallow") return 5;
  return 0;
}

std::string patch_needles_csv(const patch::PatchDesign& design, const patch::FittedPatch& fit,
                              const patch::PatchEvaluation& evaluation) {
  std::string out =
      "node,i,j,inner,on_surface,base_x_mm,base_y_mm,base_z_mm,tip_x_mm,tip_y_mm,tip_z_mm,surface_x_mm,surface_y_mm,"
      "surface_z_mm,travel_um,penetration_um,angle_deg,buckling_force_N,bending_force_N,penetrates,buckles,bends,"
      "local_pitch_um,performance_index_per_um,status\n";
  for (int k = 0; k < design.node_count(); ++k) {
    const patch::NeedleState& s = evaluation.needles[k];
    const Eigen::Vector3d b = s.base * 1e3, t = s.tip * 1e3, p = s.surface_point * 1e3;
    const auto surface_part = s.hits_surface ? fmt::format("{:.9g},{:.9g},{:.9g}", p.x(), p.y(), p.z()) : ",,";
    out += fmt::format("{},{},{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{},{},"
                       "{},{:.6g},{:.6g},{}\n",
                       k, design.column(k), design.row(k), design.inner[k] ? 1 : 0,
                       !fit.on_surface.empty() && fit.on_surface[k] ? 1 : 0, b.x(), b.y(), b.z(), t.x(), t.y(), t.z(),
                       surface_part, s.travel * 1e6, s.penetration * 1e6, s.angle * 180 / M_PI, s.buckling_force,
                       s.bending_force, s.penetrates ? 1 : 0, s.buckles ? 1 : 0, s.bends ? 1 : 0, s.local_pitch * 1e6,
                       s.performance_index * 1e-6, s.status);
  }
  return out;
}

nlohmann::json patch_summary_json(const patch::PatchDesign& design, const patch::FitOptions& fit_options,
                                  const patch::FittedPatch& fit, const patch::PatchEvaluation& e, double fit_ms) {
  const analysis::PerformanceIndexResult& r = e.reference;
  nlohmann::json j;
  j["kind"] = patch::to_string(fit_options.kind);
  j["needles"] = design.node_count();
  j["penetrating"] = e.penetrating;
  j["buckled"] = e.buckled;
  j["bent"] = e.bent;
  j["nodes_on_surface"] = e.on_surface;
  j["performance_index_mean_per_um"] = e.performance_index.mean * 1e-6;
  j["performance_index_total_per_um"] = e.performance_index.total * 1e-6;
  j["performance_index_per_um"] = stats_json(e.performance_index, 1e-6, true);
  j["buckling_force_N"] = stats_json(e.buckling_force, 1);
  j["bending_force_N"] = stats_json(e.bending_force, 1);
  j["angle_deg"] = stats_json(e.angle, 180 / M_PI);
  j["travel_um"] = stats_json(e.travel, 1e6);
  j["spring_energy_mJ"] = stats_json(e.spring_energy, 1e3, true);
  j["puncture_force_N"] = r.puncture_force;
  j["deformation_um"] = r.deformation * 1e6;
  j["critical_buckling_load_N"] = r.buckling.critical_load;
  j["critical_bending_load_N"] = r.critical_bending_load ? nlohmann::json(*r.critical_bending_load) : nullptr;
  j["reference_performance_index_per_um"] = r.performance_index * 1e-6;
  j["patch"] = {{"size_mm", design.width_u * 1e3},
                {"needles_per_row", design.nodes_u},
                {"pitch_um", design.pitch_u * 1e6},
                {"spring_constant_N_per_mm", design.springs.empty() ? 0.0 : design.springs.front().stiffness * 1e-3}};
  if (fit_options.kind == patch::PatchKind::Flexible) {
    j["patch"]["max_spring_energy_mJ"] = fit_options.flexible.max_spring_energy * 1e3;
  }
  if (fit_options.kind == patch::PatchKind::Equilibrium) {
    j["patch"]["node_load_N"] = fit_options.equilibrium.node_load;
    j["iterations"] = fit.iterations;
  }
  j["first_node"] = fit.first_node;
  j["status"] = patch::to_string(fit.status);
  j["reason"] = fit.reason;
  j["affected_nodes"] = fit.affected_nodes;
  j["fit_ms"] = fit_ms;
  return j;
}

VtuGrid surface_grid(const geometry::SurfaceMesh& surface, const Eigen::Vector3d& center, double radius) {
  const geometry::TriangleMesh& mesh = surface.mesh();
  VtuGrid grid;
  std::vector<int> index(mesh.vertices.size(), -1);
  const double r2 = radius * radius;
  VtuField normal{"normal", 3, {}};
  for (const auto& tri : mesh.triangles) {
    bool near = std::isinf(radius);
    for (const int v : tri) near = near || (mesh.vertices[v] - center).squaredNorm() <= r2;
    if (!near) continue;
    std::vector<int> cell;
    for (const int v : tri) {
      if (index[v] < 0) {
        index[v] = static_cast<int>(grid.points.size());
        grid.points.push_back(mesh.vertices[v]);
        const Eigen::Vector3d& n = surface.vertex_normal(v);
        normal.values.insert(normal.values.end(), {n.x(), n.y(), n.z()});
      }
      cell.push_back(index[v]);
    }
    grid.cells.push_back(cell);
    grid.cell_types.push_back(VtkCellType::Triangle);
  }
  grid.point_fields.push_back(std::move(normal));
  return grid;
}

VtuGrid patch_grid(const patch::PatchDesign& design, const patch::FittedPatch& fit,
                   const std::vector<double>& geodesic_strain) {
  VtuGrid grid;
  grid.points = fit.positions;
  VtuField on_surface{"on_surface", 1, {}}, inner{"inner", 1, {}}, normal{"normal", 3, {}};
  for (int k = 0; k < design.node_count(); ++k) {
    on_surface.values.push_back(!fit.on_surface.empty() && fit.on_surface[k] ? 1 : 0);
    inner.values.push_back(design.inner[k] ? 1 : 0);
    normal.values.insert(normal.values.end(), {fit.normals[k].x(), fit.normals[k].y(), fit.normals[k].z()});
  }
  const std::vector<double> energies = patch::spring_energies(design, fit.positions);
  VtuField energy{"strain_energy_mJ", 1, {}}, stretch{"stretch_um", 1, {}}, direction{"direction", 1, {}};
  for (std::size_t s = 0; s < design.springs.size(); ++s) {
    const patch::Spring& spring = design.springs[s];
    grid.cells.push_back({spring.a, spring.b});
    grid.cell_types.push_back(VtkCellType::Line);
    energy.values.push_back(energies[s] * 1e3);
    stretch.values.push_back(((fit.positions[spring.b] - fit.positions[spring.a]).norm() - spring.rest_length) * 1e6);
    direction.values.push_back(static_cast<double>(spring.direction));
  }
  grid.point_fields = {on_surface, inner, normal};
  grid.cell_fields = {energy, stretch, direction};
  if (!geodesic_strain.empty()) grid.cell_fields.push_back({"geodesic_strain", 1, geodesic_strain});
  return grid;
}

VtuGrid needles_grid(const patch::PatchEvaluation& evaluation) {
  VtuGrid grid;
  VtuField buckling{"buckling_force_N", 1, {}}, bending{"bending_force_N", 1, {}}, angle{"angle_deg", 1, {}},
      failure{"failure", 1, {}}, index{"performance_index_per_um", 1, {}}, travel{"travel_um", 1, {}},
      penetration{"penetration_um", 1, {}};
  for (const patch::NeedleState& s : evaluation.needles) {
    const int first = static_cast<int>(grid.points.size());
    grid.points.push_back(s.base);
    grid.points.push_back(s.tip);
    grid.cells.push_back({first, first + 1});
    grid.cell_types.push_back(VtkCellType::Line);
    buckling.values.push_back(s.buckling_force);
    bending.values.push_back(s.bending_force);
    angle.values.push_back(s.angle * 180 / M_PI);
    failure.values.push_back(failure_code(s));
    index.values.push_back(s.performance_index * 1e-6);
    travel.values.push_back(s.travel * 1e6);
    penetration.values.push_back(s.penetration * 1e6);
  }
  grid.cell_fields = {buckling, bending, angle, failure, index, travel, penetration};
  return grid;
}

}  // namespace needlekit::io
