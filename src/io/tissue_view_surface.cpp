#include "needlekit/io/tissue_view_surface.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/tet_adjacency.hpp"

namespace needlekit::io {

namespace {

// The triangles (mesh node indices) on a compact vertex list.
TissueViewSurface compact(const std::vector<std::array<int, 3>>& triangles, std::size_t mesh_nodes) {
  TissueViewSurface surface;
  std::vector<int> vertex_of(mesh_nodes, -1);
  for (const std::array<int, 3>& t : triangles) {
    for (int n : t) vertex_of[n] = 0;
  }
  for (std::size_t n = 0; n < vertex_of.size(); ++n) {
    if (vertex_of[n] < 0) continue;
    vertex_of[n] = static_cast<int>(surface.nodes.size());
    surface.nodes.push_back(static_cast<int>(n));
  }
  surface.triangles.reserve(triangles.size());
  for (const std::array<int, 3>& t : triangles) {
    surface.triangles.push_back({static_cast<std::uint32_t>(vertex_of[t[0]]), static_cast<std::uint32_t>(vertex_of[t[1]]),
                                 static_cast<std::uint32_t>(vertex_of[t[2]])});
  }
  return surface;
}

}  // namespace

TissueViewSurface tissue_view_surface(const mesh::TetMesh& tissue) {
  return compact(mesh::boundary_surface(tissue, mesh::tet_topology(tissue)).triangles, tissue.nodes.size());
}

TissueViewSurface top_surface(const TissueViewSurface& surface, const mesh::TetMesh& tissue) {
  double size = 0;
  for (const Eigen::Vector3d& p : tissue.nodes) size = std::max(size, p.cwiseAbs().maxCoeff());
  const double tolerance = 1e-9 * size;
  std::vector<std::array<int, 3>> kept;
  for (const std::array<std::uint32_t, 3>& t : surface.triangles) {
    const std::array<int, 3> nodes{surface.nodes[t[0]], surface.nodes[t[1]], surface.nodes[t[2]]};
    if (std::all_of(nodes.begin(), nodes.end(), [&](int n) { return std::abs(tissue.nodes[n].z()) <= tolerance; })) {
      kept.push_back(nodes);
    }
  }
  return compact(kept, tissue.nodes.size());
}

std::vector<double> nodal_average(const mesh::TetMesh& tissue, std::span<const double> element_values) {
  if (element_values.size() != tissue.tets.size()) {
    throw InvalidInput(fmt::format("nodal average: {} element values for {} tetrahedra", element_values.size(),
                                   tissue.tets.size()));
  }
  std::vector<double> sum(tissue.nodes.size(), 0.0), weight(tissue.nodes.size(), 0.0);
  for (std::size_t e = 0; e < tissue.tets.size(); ++e) {
    const auto& t = tissue.tets[e];
    const Eigen::Vector3d& a = tissue.nodes[t[0]];
    const double volume =
        std::abs((tissue.nodes[t[1]] - a).cross(tissue.nodes[t[2]] - a).dot(tissue.nodes[t[3]] - a)) / 6;
    for (int n : t) {
      sum[n] += volume * element_values[e];
      weight[n] += volume;
    }
  }
  for (std::size_t n = 0; n < sum.size(); ++n) sum[n] = weight[n] > 0 ? sum[n] / weight[n] : 0.0;
  return sum;
}

SurfaceStep surface_step(const TissueViewSurface& surface, const mesh::TetMesh& tissue,
                         std::span<const Eigen::Vector3d> displacement, std::span<const double> contact_pressure,
                         std::span<const double> von_mises_stress) {
  if (displacement.size() < tissue.nodes.size() || contact_pressure.size() < tissue.nodes.size()) {
    throw InvalidInput(fmt::format("surface step: {} displacements and {} contact pressures for a mesh of {} nodes",
                                   displacement.size(), contact_pressure.size(), tissue.nodes.size()));
  }
  const std::vector<double> stress = nodal_average(tissue, von_mises_stress);
  SurfaceStep step;
  step.positions.reserve(3 * surface.nodes.size());
  for (int n : surface.nodes) {
    const Eigen::Vector3d p = tissue.nodes[n] + displacement[n];
    step.positions.insert(step.positions.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()),
                                                 static_cast<float>(p.z())});
    step.displacement.push_back(static_cast<float>(displacement[n].norm()));
    step.von_mises_stress.push_back(static_cast<float>(stress[n]));
    step.contact_pressure.push_back(static_cast<float>(contact_pressure[n]));
  }
  return step;
}

}  // namespace needlekit::io
