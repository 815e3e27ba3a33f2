#include "needlekit/io/tet_mesh_vtu.hpp"

#include "needlekit/mesh/mesh_validation.hpp"

namespace needlekit::io {

VtuGrid tet_mesh_grid(const mesh::TetMesh& mesh) {
  VtuGrid grid;
  grid.points = mesh.nodes;
  grid.cells.reserve(mesh.tets.size());
  for (const auto& t : mesh.tets) grid.cells.push_back({t[0], t[1], t[2], t[3]});
  grid.cell_types.assign(mesh.tets.size(), VtkCellType::Tetra);
  VtuField layer{"layer", 1, {}}, modulus{"youngs_modulus_Pa", 1, {}}, poisson{"poisson_ratio", 1, {}};
  VtuField quality{"quality", 1, {}};
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const int l = mesh.tet_layer.empty() ? 0 : mesh.tet_layer[e];
    layer.values.push_back(l);
    modulus.values.push_back(mesh.layers.empty() ? 0.0 : mesh.layers[l].youngs_modulus);
    poisson.values.push_back(mesh.layers.empty() ? 0.0 : mesh.layers[l].poisson_ratio);
    const auto& t = mesh.tets[e];
    quality.values.push_back(mesh::tet_quality(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]));
  }
  grid.cell_fields = {layer, modulus, poisson, quality};
  return grid;
}

}  // namespace needlekit::io
