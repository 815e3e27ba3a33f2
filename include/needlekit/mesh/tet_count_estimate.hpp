// How many tetrahedra Gmsh will make for a layered block (layered_block_mesh.hpp), estimated from the block and its
// size fields before meshing, so that a block that would take hours or exhaust memory is refused first.
//
// The estimate integrates the element density rho(h) = kTetsPerCubicSize / h^3 over the block, with h the size
// field of layered_block_mesh: size_far everywhere, size_at_site within refinement_radius of each site (a half
// ball under the top surface), growing by size_gradient outside it, and each thin layer's cap. Overlapping regions
// are added, so the estimate errs high; tests/unit/test_tet_count_estimate.cpp holds it within a factor of 2 of
// Gmsh's count on small blocks.
#pragma once
#include "needlekit/mesh/layered_block_mesh.hpp"

namespace needlekit::mesh {

// Tetrahedra per h^3 of volume meshed at size h (a regular tetrahedron of edge h fills h^3 / (6 sqrt 2), 8.5 per h^3;
// Gmsh's meshes, calibrated on the default skin block, have about this many).
inline constexpr double kTetsPerCubicSize = 6.0;

// The estimated tetrahedron count of the block (its layers: options.layers, or the skin layers when empty). With
// split, the count after splitting (about the same as without). Assumes valid options.
double estimated_tetrahedra(const LayeredBlockOptions& options);

}  // namespace needlekit::mesh
