// Which layer each tetrahedron belongs to, from the layer thicknesses (top to bottom, the top surface at z = 0, depth
// = -z), for meshes whose elements do not follow the layer interfaces (a homogeneous mesh, an imported mesh).
#pragma once
#include <vector>

#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

enum class LayerRule {
  // Dissertation §3.3.2 generalised to N layers: a tetrahedron belongs to the topmost layer that holds any of its
  // nodes (SC if a node lies within 20 um of the surface; DM if every node lies below 160 um; else EP).
  Nodes,
  // The layer that holds the element's centroid.
  Centroid,
};

struct LayerAssignmentOptions {
  LayerRule rule = LayerRule::Nodes;
  double interface_tolerance = 1e-9;  // relative to the total thickness, [0, 1e-3]: a node this close to an
                                      // interface counts as lying in the layer below it (nodes on a conforming
                                      // interface then never pull an element into the layer above)
};

// One layer index per tetrahedron of `mesh` (its nodes and tets), for the layers `layers` (their thicknesses and
// order; the last layer also takes anything deeper). Throws InvalidInput for invalid layers.
std::vector<int> tet_layers(const TetMesh& mesh, const std::vector<TissueLayer>& layers,
                            const LayerAssignmentOptions& options = {});

}  // namespace needlekit::mesh
