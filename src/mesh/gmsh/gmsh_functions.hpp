// Private to the Gmsh module (src/mesh/gmsh/): its two functions, which throw; gmsh_module_entry.cpp turns their
// exceptions into GmshError for the library (src/mesh/gmsh_module.hpp).
#pragma once
#include <string>
#include <vector>

#include "../gmsh_module.hpp"

namespace needlekit::mesh::detail {

// The layered block's geometry, size fields and HXT mesh, as a TetMesh in m (layered_block_gmsh.cpp).
TetMesh gmsh_layered_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers);

// The tetrahedra and physical volume groups of a .msh file (msh_read_gmsh.cpp).
MshContents gmsh_read_msh(const std::string& file, const std::vector<TissueLayer>& layers);

}  // namespace needlekit::mesh::detail
