// A tetrahedral tissue mesh (dissertation §3.3): node list, tetrahedron list (right-hand rule), and per-element
// layer and material. SI units (m, Pa).
//
// Frame convention shared by the whole FE side of needlekit: the tissue's top (free) surface is the plane z = 0,
// the tissue occupies z <= 0, and needles approach from z > 0 moving in -z. Depth below the surface is -z.
#pragma once
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "needlekit/materials/tissue_layer.hpp"

namespace needlekit::mesh {

// The layers a mesh's elements refer to (declared with the tissue presets).
using materials::TissueLayer;

// A tetrahedron whose stress-free shape is not the one its nodes give (a rezoned mesh, mesh/rezoned_mesh.hpp): its
// own reference edges [X1 - X0, X2 - X0, X3 - X0] (m, right-handed). The solver measures the tetrahedron's
// deformation against them, F = (its nodes' deformed edges) * edges^-1, and its node positions only place it.
struct OwnReference {
  int tet = 0;
  Eigen::Matrix3d edges;
};

struct TetMesh {
  std::vector<Eigen::Vector3d> nodes;     // m
  std::vector<std::array<int, 4>> tets;   // node indices, right-hand rule: (p2-p1)x(p3-p1).(p4-p1) > 0 (Fig 3.2)
                                          // (not required of a tetrahedron with its own reference)
  std::vector<int> tet_layer;             // per tet, index into layers
  std::vector<TissueLayer> layers;        // E and nu of each element are layers[tet_layer[e]]
  std::vector<OwnReference> own_reference;  // usually empty; at most one per tetrahedron
};

}  // namespace needlekit::mesh
