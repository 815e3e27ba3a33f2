// One tissue layer: its name (a Gmsh physical group / a config entry), thickness and linear-elastic constants. The
// tissue presets (tissue_presets.hpp) are lists of them; a tetrahedral mesh (mesh/tet_mesh.hpp) refers to them by
// index, so materials/ needs nothing from mesh/.
#pragma once
#include <string>

namespace needlekit::materials {

struct TissueLayer {
  std::string name;             // e.g. "stratum corneum"
  double thickness = 0;         // m, > 0 (the last layer of a block may take the rest of the block's height)
  double youngs_modulus = 0;    // Pa, > 0
  double poisson_ratio = 0.4;   // (-1, 0.5)
};

}  // namespace needlekit::materials
