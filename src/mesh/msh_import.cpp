#include "needlekit/mesh/msh_import.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

#include "gmsh_session.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/mesh_validation.hpp"

namespace needlekit::mesh {
namespace {

constexpr int kGmshTet4 = 4;
constexpr int kGmshTet10 = 11;

struct PhysicalVolume {
  std::string name;  // the group's number when it has no name
  bool named = false;
  std::vector<int> entities;
};

// Tetrahedra (4 corner node tags each) of the volume entity `tag` (-1: all).
std::vector<std::size_t> corner_node_tags(int tag) {
  std::vector<std::size_t> corners;
  for (int type : {kGmshTet4, kGmshTet10}) {
    std::vector<std::size_t> element_tags, node_tags;
    gmsh::model::mesh::getElementsByType(type, element_tags, node_tags, tag);
    const std::size_t per = type == kGmshTet4 ? 4 : 10;
    for (std::size_t e = 0; e < element_tags.size(); ++e) {
      corners.insert(corners.end(), node_tags.begin() + static_cast<long>(e * per),
                     node_tags.begin() + static_cast<long>(e * per + 4));
    }
  }
  return corners;
}

}  // namespace

MshImportResult msh_import(const std::filesystem::path& file, const MshImportOptions& options) {
  const std::string name = file.string();
  if (!std::isfinite(options.unit) || options.unit <= 0) {
    throw InvalidInput(fmt::format("{}: unit = {} m; expected a positive length", name, options.unit));
  }
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw IoError(fmt::format("{}: cannot read: no such file", name));
  }
  MshImportResult result;
  TetMesh& mesh = result.mesh;
  std::vector<std::vector<std::size_t>> layer_corners;  // node tags, 4 per tet, per layer
  std::vector<std::size_t> node_tags;
  std::vector<double> coords;
  {
    detail::GmshSession session;
    try {
      gmsh::open(name);
    } catch (...) {
      throw IoError(fmt::format("{}: cannot read as a Gmsh mesh: {}", name, detail::gmsh_error_message()));
    }
    try {
      gmsh::vectorpair groups;
      gmsh::model::getPhysicalGroups(groups, 3);
      std::vector<PhysicalVolume> volumes;
      for (const auto& [dim, tag] : groups) {
        PhysicalVolume v;
        gmsh::model::getPhysicalName(dim, tag, v.name);
        v.named = !v.name.empty();
        if (!v.named) v.name = std::to_string(tag);
        gmsh::model::getEntitiesForPhysicalGroup(dim, tag, v.entities);
        volumes.push_back(std::move(v));
      }
      auto corners_of = [](const PhysicalVolume& v) {
        std::vector<std::size_t> c;
        for (int entity : v.entities) {
          auto more = corner_node_tags(entity);
          c.insert(c.end(), more.begin(), more.end());
        }
        return c;
      };
      const std::vector<std::size_t> all = corner_node_tags(-1);
      if (all.empty()) {
        throw InvalidInput(fmt::format("{}: no tetrahedra; expected a volume mesh of 4- or 10-node tetrahedra", name));
      }
      std::vector<std::string> names;
      for (const auto& v : volumes) names.push_back('"' + v.name + '"');
      if (options.layers.empty()) {
        if (volumes.empty()) {
          throw InvalidInput(fmt::format("{}: no physical volume groups; name the layers in the file or give one layer",
                                         name));
        }
        for (const auto& v : volumes) {
          mesh.layers.push_back({v.name, 0, 0, 0.4});
          layer_corners.push_back(corners_of(v));
        }
      } else if (options.layers.size() == 1 && std::none_of(volumes.begin(), volumes.end(),
                                                             [](const auto& v) { return v.named; })) {
        mesh.layers = options.layers;
        layer_corners.push_back(all);
      } else {
        for (const TissueLayer& layer : options.layers) {
          auto it = std::find_if(volumes.begin(), volumes.end(), [&](const auto& v) { return v.name == layer.name; });
          if (it == volumes.end()) {
            throw InvalidInput(fmt::format("{}: no physical volume group named \"{}\" (layer {}); the file has {}",
                                           name, layer.name, mesh.layers.size(),
                                           names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
          }
          mesh.layers.push_back(layer);
          layer_corners.push_back(corners_of(*it));
        }
      }
      std::size_t in_layers = 0;
      for (const auto& c : layer_corners) in_layers += c.size();
      if (in_layers != all.size()) {
        throw InvalidInput(fmt::format("{}: {} of the {} tetrahedra are in the layers' physical volumes; expected "
                                       "every tetrahedron in exactly one layer (groups: {})",
                                       name, in_layers / 4, all.size() / 4, fmt::join(names, ", ")));
      }
      std::vector<double> parametric;
      gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
    } catch (const InvalidInput&) {
      throw;
    } catch (...) {
      throw IoError(fmt::format("{}: cannot read the mesh: {}", name, detail::gmsh_error_message()));
    }
  }
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
