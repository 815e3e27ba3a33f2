#include "needlekit/patch/fitted_patch.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace needlekit::patch {

std::string_view to_string(FitStatus status) { return name_of(kFitStatusNames, status); }

std::vector<Eigen::Vector3d> flat_positions(const PatchDesign& design, const PatchFrame& frame, double height) {
  std::vector<Eigen::Vector3d> positions(design.node_count());
  const Eigen::Vector3d origin = frame.surface_point - height * frame.approach;
  for (int k = 0; k < design.node_count(); ++k) {
    positions[k] = origin + design.rest_positions[k].x() * frame.u + design.rest_positions[k].y() * frame.v;
  }
  return positions;
}

std::vector<double> spring_energies(const PatchDesign& design, const std::vector<Eigen::Vector3d>& positions) {
  std::vector<double> energies(design.springs.size());
  for (std::size_t s = 0; s < design.springs.size(); ++s) {
    const Spring& spring = design.springs[s];
    const double stretch = (positions[spring.b] - positions[spring.a]).norm() - spring.rest_length;  // Eq 5.14
    energies[s] = 0.5 * spring.stiffness * stretch * stretch;                                         // Eq 5.13
  }
  return energies;
}

std::vector<Eigen::Vector3d> grid_normals(const PatchDesign& design, const std::vector<Eigen::Vector3d>& positions,
                                          const Eigen::Vector3d& approach) {
  std::vector<Eigen::Vector3d> normals(design.node_count());
  for (int j = 0; j < design.nodes_v; ++j) {
    for (int i = 0; i < design.nodes_u; ++i) {
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, design.nodes_u - 1);
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, design.nodes_v - 1);
      const Eigen::Vector3d du = positions[design.node(i1, j)] - positions[design.node(i0, j)];
      const Eigen::Vector3d dv = positions[design.node(i, j1)] - positions[design.node(i, j0)];
      Eigen::Vector3d n = du.cross(dv);
      if (n.norm() == 0) n = -approach;
      n.normalize();
      if (n.dot(approach) > 0) n = -n;
      normals[design.node(i, j)] = n;
    }
  }
  return normals;
}

}  // namespace needlekit::patch
