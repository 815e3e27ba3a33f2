// Reading a .msh file with Gmsh: its tetrahedra (4- and 10-node; corner nodes only) grouped by the physical volume
// groups that the layers name. Part of the Gmsh module; numbering and validation are in src/mesh/msh_import.cpp.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "gmsh_functions.hpp"
#include "gmsh_session.hpp"
#include "needlekit/core/errors.hpp"

namespace needlekit::mesh::detail {
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

MshContents gmsh_read_msh(const std::string& name, const std::vector<TissueLayer>& layers) {
  MshContents contents;
  GmshSession session;
  try {
    gmsh::open(name);
  } catch (...) {
    throw IoError(fmt::format("{}: cannot read as a Gmsh mesh: {}", name, gmsh_error_message()));
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
    if (layers.empty()) {
      if (volumes.empty()) {
        throw InvalidInput(fmt::format("{}: no physical volume groups; name the layers in the file or give one layer",
                                       name));
      }
      for (const auto& v : volumes) {
        contents.layers.push_back({v.name, 0, 0, 0.4});
        contents.layer_corners.push_back(corners_of(v));
      }
    } else if (layers.size() == 1 && std::none_of(volumes.begin(), volumes.end(),
                                                           [](const auto& v) { return v.named; })) {
      contents.layers = layers;
      contents.layer_corners.push_back(all);
    } else {
      for (const TissueLayer& layer : layers) {
        auto it = std::find_if(volumes.begin(), volumes.end(), [&](const auto& v) { return v.name == layer.name; });
        if (it == volumes.end()) {
          throw InvalidInput(fmt::format("{}: no physical volume group named \"{}\" (layer {}); the file has {}",
                                         name, layer.name, contents.layers.size(),
                                         names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
        }
        contents.layers.push_back(layer);
        contents.layer_corners.push_back(corners_of(*it));
      }
    }
    std::size_t in_layers = 0;
    for (const auto& c : contents.layer_corners) in_layers += c.size();
    if (in_layers != all.size()) {
      throw InvalidInput(fmt::format("{}: {} of the {} tetrahedra are in the layers' physical volumes; expected "
                                     "every tetrahedron in exactly one layer (groups: {})",
                                     name, in_layers / 4, all.size() / 4, fmt::join(names, ", ")));
    }
    std::vector<double> parametric;
    gmsh::model::mesh::getNodes(contents.node_tags, contents.coords, parametric, -1, -1, false, false);
  } catch (const InvalidInput&) {
    throw;
  } catch (...) {
    throw IoError(fmt::format("{}: cannot read the mesh: {}", name, gmsh_error_message()));
  }
  return contents;
}

}  // namespace needlekit::mesh::detail
