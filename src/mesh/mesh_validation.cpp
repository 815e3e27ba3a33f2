#include "needlekit/mesh/mesh_validation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "needlekit/core/errors.hpp"

namespace needlekit::mesh {
namespace {

std::string first_indices(const std::vector<int>& indices) {
  constexpr std::size_t kShown = 10;
  const std::size_t n = std::min(indices.size(), kShown);
  std::string out = fmt::format("{}", fmt::join(indices.begin(), indices.begin() + static_cast<long>(n), ", "));
  if (indices.size() > kShown) out += ", ...";
  return out;
}

}  // namespace

double signed_volume(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3,
                     const Eigen::Vector3d& p4) {
  return (p2 - p1).cross(p3 - p1).dot(p4 - p1) / 6.0;
}

double tet_quality(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3,
                   const Eigen::Vector3d& p4) {
  const Eigen::Vector3d u = p2 - p1, v = p3 - p1, w = p4 - p1;
  const double six_volume = u.cross(v).dot(w);
  if (six_volume == 0) return 0;
  // Inscribed radius r = 3V / (sum of face areas).
  const double area = 0.5 * (u.cross(v).norm() + v.cross(w).norm() + w.cross(u).norm() + (p3 - p2).cross(p4 - p2).norm());
  const double r_in = 0.5 * std::abs(six_volume) / area;
  // Circumcentre relative to p1: (|u|^2 v x w + |v|^2 w x u + |w|^2 u x v) / (2 u . (v x w)).
  const Eigen::Vector3d centre =
      (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / (2 * six_volume);
  return std::min(1.0, 3.0 * r_in / centre.norm());
}

TetMeshCheck tet_mesh_check(const TetMesh& mesh, const TetMeshCheckOptions& options, std::string_view where) {
  const int nodes = static_cast<int>(mesh.nodes.size());
  if (!mesh.tet_layer.empty() && mesh.tet_layer.size() != mesh.tets.size()) {
    throw InvalidInput(fmt::format("{}: {} layer indices for {} tetrahedra; expected one per tetrahedron", where,
                                   mesh.tet_layer.size(), mesh.tets.size()));
  }
  for (std::size_t e = 0; e < mesh.tet_layer.size(); ++e) {
    if (mesh.tet_layer[e] < 0 || mesh.tet_layer[e] >= static_cast<int>(mesh.layers.size())) {
      throw InvalidInput(fmt::format("{}: tetrahedron {} has layer {}; the mesh has {} layers", where, e,
                                     mesh.tet_layer[e], mesh.layers.size()));
    }
  }
  TetMeshCheck check;
  check.quality.resize(mesh.tets.size());
  check.min_quality = mesh.tets.empty() ? 0 : std::numeric_limits<double>::infinity();
  double sum = 0;
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const auto& t = mesh.tets[e];
    for (int a = 0; a < 4; ++a) {
      if (t[a] < 0 || t[a] >= nodes) {
        throw InvalidInput(fmt::format("{}: tetrahedron {} refers to node {}; the mesh has {} nodes", where, e, t[a],
                                       nodes));
      }
      for (int b = 0; b < a; ++b) {
        if (t[a] == t[b]) {
          throw InvalidInput(fmt::format("{}: tetrahedron {} repeats node {}", where, e, t[a]));
        }
      }
    }
    const auto& p = mesh.nodes;
    const double v = signed_volume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
    const double q = tet_quality(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
    check.quality[e] = q;
    check.volume += std::abs(v);
    if (v < 0) check.inverted.push_back(static_cast<int>(e));
    if (q < options.degenerate_quality) check.degenerate.push_back(static_cast<int>(e));
    check.min_quality = std::min(check.min_quality, q);
    sum += q;
  }
  check.mean_quality = mesh.tets.empty() ? 0 : sum / static_cast<double>(mesh.tets.size());
  return check;
}

void validate(const TetMesh& mesh, std::string_view where, const TetMeshCheckOptions& options) {
  if (mesh.tets.empty()) throw InvalidInput(fmt::format("{}: no tetrahedra", where));
  const TetMeshCheck check = tet_mesh_check(mesh, options, where);
  std::string problems;
  if (!check.inverted.empty()) {
    problems += fmt::format("{} inverted (left-handed, negative volume) tetrahedra: {}", check.inverted.size(),
                            first_indices(check.inverted));
  }
  if (!check.degenerate.empty()) {
    if (!problems.empty()) problems += "; ";
    problems += fmt::format("{} degenerate tetrahedra (quality < {}): {}", check.degenerate.size(),
                            options.degenerate_quality, first_indices(check.degenerate));
  }
  if (!problems.empty()) {
    throw InvalidInput(fmt::format("{}: {}; expected right-handed, non-degenerate tetrahedra (0-based indices)",
                                   where, problems));
  }
}

int reoriented_count(TetMesh& mesh) {
  int swapped = 0;
  for (auto& t : mesh.tets) {
    if (signed_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]) < 0) {
      std::swap(t[1], t[2]);
      ++swapped;
    }
  }
  return swapped;
}

std::vector<LayerQuality> layer_quality(const TetMesh& mesh) {
  std::vector<LayerQuality> out(mesh.layers.size());
  for (std::size_t l = 0; l < out.size(); ++l) {
    out[l].name = mesh.layers[l].name;
    out[l].min_quality = std::numeric_limits<double>::infinity();
  }
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const auto& t = mesh.tets[e];
    const double q = tet_quality(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
    LayerQuality& l = out.at(static_cast<std::size_t>(mesh.tet_layer.at(e)));
    ++l.tets;
    l.min_quality = std::min(l.min_quality, q);
    l.mean_quality += q;
  }
  for (LayerQuality& l : out) {
    if (l.tets == 0) {
      l.min_quality = 0;
    } else {
      l.mean_quality /= l.tets;
    }
  }
  return out;
}

}  // namespace needlekit::mesh
