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

struct TetMesh {
  std::vector<Eigen::Vector3d> nodes;     // m
  std::vector<std::array<int, 4>> tets;   // node indices, right-hand rule: (p2-p1)x(p3-p1).(p4-p1) > 0 (Fig 3.2)
  std::vector<int> tet_layer;             // per tet, index into layers
  std::vector<TissueLayer> layers;        // E and nu of each element are layers[tet_layer[e]]
};

}  // namespace needlekit::mesh
