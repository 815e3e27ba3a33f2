#include "needlekit/io/scale_warnings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "needlekit/core/plausible_scale.hpp"
#include "needlekit/mesh/cell_replication.hpp"

namespace needlekit::io {
namespace {

Eigen::Vector3d extent_of(const geometry::TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d low = mesh.vertices.front(), high = low;
  for (const Eigen::Vector3d& v : mesh.vertices) low = low.cwiseMin(v), high = high.cwiseMax(v);
  return high - low;
}

double median_edge(const geometry::TriangleMesh& mesh) {
  std::vector<double> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) edges.push_back((mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm());
  }
  if (edges.empty()) return 0;
  std::nth_element(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(edges.size() / 2), edges.end());
  return edges[edges.size() / 2];
}

void add(std::vector<std::string>& warnings, std::optional<std::string> warning) {
  if (warning) warnings.push_back(std::move(*warning));
}

}  // namespace

std::vector<std::string> needle_scale_warnings(const needle::NeedleGeometry& needle) {
  std::vector<std::string> warnings;
  add(warnings, units::implausible_length("needle.length", needle.length, kPlausibleNeedleLength[0],
                                          kPlausibleNeedleLength[1]));
  return warnings;
}

std::vector<std::string> surface_scale_warnings(const geometry::TriangleMesh& surface, std::string_view unit_key) {
  std::vector<std::string> warnings;
  add(warnings, units::implausible_length(fmt::format("the body surface's largest extent (with {})", unit_key),
                                          extent_of(surface).maxCoeff(), kPlausibleBodyExtent[0],
                                          kPlausibleBodyExtent[1]));
  return warnings;
}

std::vector<std::string> patch_scale_warnings(const geometry::TriangleMesh& surface, const patch::PatchDesign& design) {
  std::vector<std::string> warnings = surface_scale_warnings(surface, "surface.unit");
  for (std::string& warning : needle_scale_warnings(design.needle)) warnings.push_back(std::move(warning));
  const double edge = median_edge(surface);
  const double size = std::min(design.width_u, design.width_v);
  if (size < edge) {
    warnings.push_back(fmt::format("patch.size {} is smaller than the body surface's median edge {}: the patch rests "
                                   "on one or two flat triangles (a unit mistake in surface.unit or patch.size, or a "
                                   "mesh too coarse for this patch)",
                                   units::readable_length(size), units::readable_length(edge)));
  }
  return warnings;
}

std::vector<std::string> indentation_scale_warnings(const insertion::IndentationCase& c) {
  std::vector<std::string> warnings;
  const Eigen::Vector3d needle = extent_of(c.needle);
  add(warnings, units::implausible_length(c.geometry ? "needle.length" : "the needle mesh's height (with "
                                                                         "needle.mesh_unit)",
                                          needle.z(), kPlausibleNeedleLength[0], kPlausibleNeedleLength[1]));
  double width = c.block.width, length = c.block.length;
  if (c.tissue_mesh && !c.tissue_mesh->nodes.empty()) {
    Eigen::Vector3d low = c.tissue_mesh->nodes.front(), high = low;
    for (const Eigen::Vector3d& p : c.tissue_mesh->nodes) low = low.cwiseMin(p), high = high.cwiseMax(p);
    width = high.x() - low.x(), length = high.y() - low.y();
  }
  const double across = std::max(needle.x(), needle.y()), block = std::min(width, length);
  if (across > block) {
    warnings.push_back(fmt::format("the needle is {} across, wider than the {} x {} tissue block{}", 
                                   units::readable_length(across), units::readable_length(width),
                                   units::readable_length(length),
                                   c.geometry ? "" : ": is needle.mesh_unit right (a needle STL in um declared as mm "
                                                     "is 1000x too large)?"));
  }
  if (c.angle > insertion::kSteepAngle) {
    warnings.push_back(fmt::format("loading.angle = {:.4g} deg is steeper than 45 deg from the skin's normal: the "
                                   "needle slides along the surface more than it enters, and the block's sides (fixed) "
                                   "come nearer to the tip's path",
                                   c.angle * 180 / M_PI));
  }
  if (c.array && c.array->symmetry != insertion::ArraySymmetry::None) {
    const bool quarter = c.array->symmetry == insertion::ArraySymmetry::Quarter;
    for (int axis : {0, 1}) {
      if (axis == 0 && !quarter) continue;
      const double offset = insertion::off_mirror_plane(c, axis);
      if (offset == 0) continue;
      const char* name = axis == 0 ? "x" : "y";
      warnings.push_back(fmt::format(
          "array.symmetry = \"{}\" mirrors the needles across {} = 0, and this needle is not its own mirror "
          "image there (its surface's centroid lies {} off its axis along {}: a bevel faces along loading.azimuth): "
          "the model is of a patch whose needles at {} < 0 are mirror images, their bevels turned the other way; for "
          "a patch of identical needles use symmetry = {}",
          name_of(insertion::kArraySymmetryNames, c.array->symmetry), name, units::readable_length(offset), name, name,
          axis == 0 && insertion::off_mirror_plane(c, 1) == 0 ? "\"half\" or \"none\"" : "\"none\""));
    }
  }
  if (c.array && !c.tissue_mesh && c.needles.size() > 1) {
    // An array's block is assembled from copies of one cell where it can be (mesh/cell_replication.hpp); otherwise
    // it is one Delaunay of the whole block, slow for a large array.
    const insertion::IndentationCase solved = insertion::modelled_case(c);
    mesh::LayeredBlockOptions block = solved.block;
    block.insertion_sites.clear();
    for (const insertion::NeedleSite& site : solved.needles) block.insertion_sites.push_back(site.position);
    if (solved.needles.size() > 1) {
      if (const mesh::SiteGridCheck cells = mesh::site_grid(block, insertion::cell_lattice(*c.array)); !cells.grid) {
        warnings.push_back(fmt::format("the array's block is meshed whole, not from copies of one cell: {}",
                                       cells.reason));
      }
    }
  }
  const double height = insertion::tissue_height(c);
  if (height > 0 && needle.z() > height) {
    warnings.push_back(fmt::format("the needle ({} long) is longer than the tissue block is high ({}): a unit mistake "
                                   "in the needle's length or the tissue's thickness?",
                                   units::readable_length(needle.z()), units::readable_length(height)));
  }
  if (c.solver.contact == fem::ContactModel::Surface && c.depth > needle.z()) {
    warnings.push_back(fmt::format("loading.depth = {} is deeper than the needle is long ({}): under surface contact "
                                   "its back end then enters the tissue and pushes it back; make the needle longer or "
                                   "the depth shorter",
                                   units::readable_length(c.depth), units::readable_length(needle.z())));
  }
  return warnings;
}

}  // namespace needlekit::io
