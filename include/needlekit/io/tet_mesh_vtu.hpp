// A tissue mesh as a VTU grid: points in m, linear tetrahedra, and the cell fields layer (index), youngs_modulus_Pa,
// poisson_ratio and quality (gamma). Writers of FE results append their own point and cell fields.
#pragma once
#include "needlekit/io/vtu_writer.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::io {

VtuGrid tet_mesh_grid(const mesh::TetMesh& mesh);

}  // namespace needlekit::io
