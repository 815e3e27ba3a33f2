// Private to src/mesh: an array cell that is its own mirror image across both of its centre lines, assembled from its
// quadrant (gmsh_module.hpp, CellLayout::quadrant). A cell meshed whole by Delaunay is not symmetric even where the
// array is: on the 3 x 3 cone example the quarter model through the middle row and column, whose cells are framed
// from needle to needle, differed from the full model by +2.3 to +4.4 % per needle (docs/arrays.md). Built from
// images of one quadrant with the needle on its corner, the full model's cells (needle at the centre) and the framed
// cells (needles on the corners) are the same quadrants placed differently.
#pragma once
#include "gmsh_module.hpp"

namespace needlekit::mesh::detail {

// The whole cell with its margin pieces (CellBlockMesh, pieces 3 * py + px) from `quadrant`, the Gmsh module's mesh
// of `layout` with layout.quadrant set, from images of the quadrant: for a site at the cell's centre the quadrant is
// the cell's quadrant x, y >= 0; for sites on the corners that quadrant is the quadrant turned by a half turn (the
// site to the cell's corner) and, beyond the site, its mirror images with their margins (the half of the site's
// centred cell beyond it, then the margin of a centred cell): every needle of a square array, inside or on its
// edge, then sees four images of the same quadrant round it. The cell's quadrant is then mirrored across x = 0,
// y = 0 and both. Images share the nodes on their planes, which the quadrant has exactly on its planes (a node within
// 1e-9 of the pitch of one is put on it), so they are merged by identical coordinates. A margin piece is kept on
// the sides whose margin is > 0 (each side of an axis has no margin or the same one: mirrors_from_a_quadrant). A
// reflected image's tetrahedra are renumbered to stay right-handed.
CellBlockMesh mirrored_cell(const CellBlockMesh& quadrant, const CellLayout& layout);

// Whether the cell of `layout` can be mirrored from a quadrant: one site at the cell's centre or sites on its corners,
// no top row of sites and no circles to embed, and on each axis either side's margin 0 or both equal (with sites on
// the corners, 0 or at least half a pitch).
bool mirrors_from_a_quadrant(const CellLayout& layout, const LayeredBlockOptions& options);

}  // namespace needlekit::mesh::detail
