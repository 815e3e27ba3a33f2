// Import of a .msh file: Gmsh (in the Gmsh module, src/mesh/gmsh/msh_read_gmsh.cpp) reads the tetrahedra and
// groups; here they are numbered compactly, reoriented if asked, validated and rated.
#include "needlekit/mesh/msh_import.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "gmsh_module.hpp"
#include "msh_read_isolated.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/mesh_validation.hpp"

namespace needlekit::mesh {

MshImportResult msh_import(const std::filesystem::path& file, const MshImportOptions& options) {
  const std::string name = file.string();
  if (!std::isfinite(options.unit) || options.unit <= 0) {
    throw InvalidInput(fmt::format("{}: unit = {} m; expected a positive length", name, options.unit));
  }
  if (!std::isfinite(options.reader_cpu_limit) || options.reader_cpu_limit < 0) {
    throw InvalidInput(fmt::format("{}: reader_cpu_limit = {} s; expected 0 (none) or a positive time", name,
                                   options.reader_cpu_limit));
  }
  std::error_code status;
  if (!std::filesystem::is_regular_file(file, status)) {
    throw IoError(fmt::format("{}: cannot read: no such file", name));
  }
  MshImportResult result;
  TetMesh& mesh = result.mesh;
  detail::GmshError error;
  detail::MshContents contents = detail::read_msh_isolated(
      name, options.layers, error, {.keep_process = options.keep_reader_process, .cpu_limit = options.reader_cpu_limit});
  detail::throw_if_failed(error);
  mesh.layers = std::move(contents.layers);
  const std::vector<std::vector<std::size_t>>& layer_corners = contents.layer_corners;
  const std::vector<std::size_t>& node_tags = contents.node_tags;
  const std::vector<double>& coords = contents.coords;
  // Compact node numbering over the nodes the tetrahedra use, in Gmsh's node order.
  std::size_t max_tag = 0;
  for (std::size_t tag : node_tags) max_tag = std::max(max_tag, tag);
  std::vector<int> index_of_tag(max_tag + 1, -1);
  for (const auto& c : layer_corners) {
    for (std::size_t tag : c) {
      if (tag > max_tag) throw IoError(fmt::format("{}: element node {} has no coordinates", name, tag));
      index_of_tag[tag] = -2;  // used
    }
  }
  for (std::size_t k = 0; k < node_tags.size(); ++k) {
    int& index = index_of_tag[node_tags[k]];
    if (index != -2) continue;
    index = static_cast<int>(mesh.nodes.size());
    mesh.nodes.emplace_back(Eigen::Vector3d(coords[3 * k], coords[3 * k + 1], coords[3 * k + 2]) * options.unit);
  }
  for (std::size_t l = 0; l < layer_corners.size(); ++l) {
    const auto& c = layer_corners[l];
    for (std::size_t tag : c) {
      if (index_of_tag[tag] < 0) throw IoError(fmt::format("{}: element node {} has no coordinates", name, tag));
    }
    for (std::size_t e = 0; e + 3 < c.size(); e += 4) {
      mesh.tets.push_back({index_of_tag[c[e]], index_of_tag[c[e + 1]], index_of_tag[c[e + 2]], index_of_tag[c[e + 3]]});
      mesh.tet_layer.push_back(static_cast<int>(l));
    }
  }
  if (options.reorient) result.reoriented = reoriented_count(mesh);
  try {
    validate(mesh, name);
  } catch (const InvalidInput& e) {
    if (options.reorient || tet_mesh_check(mesh, {}, name).inverted.empty()) throw;
    throw InvalidInput(std::string(e.what()) + " (reorient renumbers left-handed tetrahedra)");
  }
  result.quality = layer_quality(mesh);
  return result;
}

}  // namespace needlekit::mesh
