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

namespace needlekit::mesh {

// One tissue layer: its name (a Gmsh physical group / a config entry) and its linear-elastic constants.
struct TissueLayer {
  std::string name;             // e.g. "stratum corneum"
  double thickness = 0;         // m, > 0 (the last layer of a block may take the rest of the block's height)
  double youngs_modulus = 0;    // Pa, > 0
  double poisson_ratio = 0.4;   // (-1, 0.5)
};

struct TetMesh {
  std::vector<Eigen::Vector3d> nodes;     // m
  std::vector<std::array<int, 4>> tets;   // node indices, right-hand rule: (p2-p1)x(p3-p1).(p4-p1) > 0 (Fig 3.2)
  std::vector<int> tet_layer;             // per tet, index into layers
  std::vector<TissueLayer> layers;        // E and nu of each element are layers[tet_layer[e]]
};

}  // namespace needlekit::mesh
