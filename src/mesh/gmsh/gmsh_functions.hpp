// Private to the Gmsh module (src/mesh/gmsh/): its functions, which throw; gmsh_module_entry.cpp turns their
// exceptions into GmshError for the library (src/mesh/gmsh_module.hpp).
#pragma once
#include <string>
#include <vector>

#include "../gmsh_module.hpp"

namespace needlekit::mesh::detail {

// The layered block's geometry, size fields and Delaunay mesh, as a TetMesh in m (layered_block_gmsh.cpp).
TetMesh gmsh_layered_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers);

// The array cell with its margins, periodic side faces and pieces, in m (cell_block_gmsh.cpp).
CellBlockMesh gmsh_cell_block(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                              const CellLayout& layout);

// The tetrahedra and physical volume groups of a .msh file (msh_read_gmsh.cpp).
MshContents gmsh_read_msh(const std::string& file, const std::vector<TissueLayer>& layers);

// The inside of a closed surface, its triangles kept (surface_refill_gmsh.cpp).
TetMesh gmsh_refill(const SurfaceToFill& surface);

}  // namespace needlekit::mesh::detail
