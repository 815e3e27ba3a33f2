// Private to src/mesh: an array cell that is its own mirror image across both of its centre lines, assembled from its
// quadrant (gmsh_module.hpp, CellLayout::quadrant). A cell meshed whole by Delaunay is not symmetric even where the
// array is: on the 3 x 3 cone example the quarter model through the middle row and column, whose cells are framed
// from needle to needle, differed from the full model by +2.3 to +4.4 % per needle (docs/arrays.md). Built from
// mirror images of one quadrant with the needle on its corner, the full model's cells (needle at the centre) and the
// framed cells (needles on the corners) are the same quadrants placed differently, and every needle of a square
// array sees the same mesh round its tip.
#pragma once
#include "gmsh_module.hpp"

namespace needlekit::mesh::detail {

// The whole cell with its margin pieces (CellBlockMesh, pieces 3 * py + px) from `quadrant`, the Gmsh module's mesh
// of `layout` with layout.quadrant set: with sites on the cell's corners the quadrant is first turned by a half turn
// about (pitch_x/4, pitch_y/4) (its site to the cell's corner, its margin beyond the cell), then it is mirrored
// across x = 0, y = 0 and both; a node on a mirror plane is shared by the images on its two sides (a node within
// 1e-9 of the pitch of the plane is put on it). A margin piece is copied to the sides whose margin is > 0 (each side
// of an axis has no margin or the same one, which array_cell_layout checks). The images across one plane are
// reflected, so their tetrahedra are renumbered to stay right-handed.
CellBlockMesh mirrored_cell(const CellBlockMesh& quadrant, const CellLayout& layout);

// Whether the cell of `layout` can be mirrored from a quadrant: one site at the cell's centre or sites on its corners,
// no top row of sites and no circles to embed, and on each axis either side's margin 0 or both equal (with sites on
// the corners, 0 or at least half a pitch).
bool mirrors_from_a_quadrant(const CellLayout& layout, const LayeredBlockOptions& options);

}  // namespace needlekit::mesh::detail
