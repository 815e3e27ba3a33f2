#include "needlekit/mesh/layer_assignment.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/materials/tissue_presets.hpp"

namespace needlekit::mesh {

std::vector<int> tet_layers(const TetMesh& mesh, const std::vector<TissueLayer>& layers,
                            const LayerAssignmentOptions& options) {
  materials::validate(layers, "layer assignment: layers");
  if (!(options.interface_tolerance >= 0 && options.interface_tolerance <= 1e-3)) {
    throw InvalidInput(fmt::format("layer assignment: interface_tolerance = {}; expected a value in [0, 1e-3]",
                                   options.interface_tolerance));
  }
  // Depth of the bottom of each layer, minus the tolerance.
  std::vector<double> bottoms;
  double depth = 0;
  for (const TissueLayer& l : layers) bottoms.push_back(depth += l.thickness);
  const double tolerance = options.interface_tolerance * depth;
  const int last = static_cast<int>(layers.size()) - 1;
  auto layer_at = [&](double z) {
    const double d = -z;
    const auto it = std::upper_bound(bottoms.begin(), bottoms.end(), d + tolerance);
    return std::min(last, static_cast<int>(it - bottoms.begin()));
  };
  std::vector<int> out(mesh.tets.size());
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const auto& t = mesh.tets[e];
    if (options.rule == LayerRule::Centroid) {
      double z = 0;
      for (int k : t) z += mesh.nodes.at(k).z();
      out[e] = layer_at(z / 4);
    } else {
      int layer = last;
      for (int k : t) layer = std::min(layer, layer_at(mesh.nodes.at(k).z()));
      out[e] = layer;
    }
  }
  return out;
}

}  // namespace needlekit::mesh
