// Import of a .msh file: Gmsh (in the Gmsh module, src/mesh/gmsh/msh_read_gmsh.cpp) reads the tetrahedra and
// groups; here they are numbered compactly, reoriented if asked, validated and rated.
#include "needlekit/mesh/msh_import.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <fmt/format.h>

#include "gmsh_module.hpp"
#include "msh_read_isolated.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/mesh_validation.hpp"

namespace needlekit::mesh {
namespace {

// Node tag -> its first position in Gmsh's node list. Tags are usually 1..n, and then a table indexed by tag; a tag
// far beyond the node count (a sparse numbering, or a malformed one: "-3050" read as 2^64 - 3050, which asked for a
// table larger than memory; found by fuzz_gmsh_msh) goes through a hash map instead.
class NodePositions {
public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  explicit NodePositions(const std::vector<std::size_t>& tags) {
    const std::size_t max_tag = tags.empty() ? 0 : *std::max_element(tags.begin(), tags.end());
    if (max_tag <= 2 * tags.size() + 1024) {
      table_.assign(max_tag + 1, kNone);
      for (std::size_t k = tags.size(); k-- > 0;) table_[tags[k]] = k;
    } else {
      map_.reserve(tags.size());
      for (std::size_t k = 0; k < tags.size(); ++k) map_.emplace(tags[k], k);
    }
  }
  std::size_t find(std::size_t tag) const {
    if (map_.empty()) return tag < table_.size() ? table_[tag] : kNone;
    const auto it = map_.find(tag);
    return it == map_.end() ? kNone : it->second;
  }

private:
  std::vector<std::size_t> table_;
  std::unordered_map<std::size_t, std::size_t> map_;
};

}  // namespace

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
  const NodePositions positions(node_tags);
  std::vector<int> index_of_position(node_tags.size(), -1);  // -2: used by a tetrahedron, not yet numbered
  const auto position_of = [&](std::size_t tag) {
    const std::size_t k = positions.find(tag);
    if (k == NodePositions::kNone) throw IoError(fmt::format("{}: element node {} has no coordinates", name, tag));
    return k;
  };
  for (const auto& c : layer_corners)
    for (std::size_t tag : c) index_of_position[position_of(tag)] = -2;
  for (std::size_t k = 0; k < node_tags.size(); ++k) {
    if (index_of_position[k] != -2) continue;
    index_of_position[k] = static_cast<int>(mesh.nodes.size());
    mesh.nodes.emplace_back(Eigen::Vector3d(coords[3 * k], coords[3 * k + 1], coords[3 * k + 2]) * options.unit);
  }
  for (std::size_t l = 0; l < layer_corners.size(); ++l) {
    const auto& c = layer_corners[l];
    const auto index = [&](std::size_t tag) { return index_of_position[position_of(tag)]; };
    for (std::size_t e = 0; e + 3 < c.size(); e += 4) {
      mesh.tets.push_back({index(c[e]), index(c[e + 1]), index(c[e + 2]), index(c[e + 3])});
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
