// A needle array's block as copies of one meshed cell (issue 36 item 5): the cell, a rectangle of every layer that
// repeats over the array (square: a pitch x pitch square centred on one needle; hexagonal: pitch by pitch*sqrt(3),
// a pair of rows, holding two needles), refined at its needles, is meshed once with its opposite side faces periodic
// (the +x faces translated copies of the -x faces, +y of -y), together with the margin pieces around it (the -x/+x
// strips, the -y/+y strips and the four corners, each as wide as the block's margin beyond the outermost cells);
// then the cell is copied to every place, each margin strip along its side and each corner once, and the nodes that
// copies share on their common faces are merged exactly (the copy's periodic face node is the neighbour's own node,
// found through the periodic pairing, not by a distance tolerance). The result is conforming (every interior face
// shared by exactly two tetrahedra), has one node per position, and every needle at the same place in its cell
// sees the same mesh under its tip. A square array's cell (no circles round the needles) is itself assembled from
// mirror images of its quadrant (src/mesh/mirrored_cell.hpp), so that the block is as symmetric as the array and a
// reduced model is a part of the full model's mesh.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

enum class BlockMeshing { WholeBlock, ReplicatedCell };
inline constexpr EnumTable<BlockMeshing, 2> kBlockMeshingNames{{
    {BlockMeshing::WholeBlock, "whole-block", "the whole block meshed by one Gmsh Delaunay (layered_block_mesh)"},
    {BlockMeshing::ReplicatedCell, "replicated-cell",
     "one needle's cell and the margins meshed once, the block assembled from their copies"},
}};

struct ArrayBlockMesh {
  LayeredBlockResult block;
  BlockMeshing meshing = BlockMeshing::WholeBlock;
  std::string reason;  // with the whole block: why the cells could not be used
};

// The cell an array repeats: a rectangle of pitch_x by pitch_y and the needles' sites in it, from its centre.
struct CellLattice {
  double pitch_x = 0, pitch_y = 0;     // m, > 0 (0: no lattice)
  std::vector<Eigen::Vector2d> sites;  // m, from the cell's centre; the first one the lowest in x and in y
};
// A square array of `pitch`: one site at the centre of a pitch x pitch cell (the site's Voronoi cell).
CellLattice square_lattice(double pitch);
// A hexagonal array of `pitch` (rows pitch*sqrt(3)/2 apart, every other row shifted by +pitch/2): a pair of rows in
// a pitch by pitch*sqrt(3) cell, the sites at (-pitch/4, -pitch*sqrt(3)/4) and (+pitch/4, +pitch*sqrt(3)/4). Only an
// even number of rows is whole pairs; the last row of an odd number lies in the +y margin (SiteGrid::top_row_sites).
CellLattice hexagonal_lattice(double pitch);

// The block of an array of `lattice` whose needles are options.insertion_sites: assembled from copies of one cell
// (replicated_cells) when site_grid finds the grid, else meshed whole (layered_block_mesh), saying why. The options'
// split and coarse level apply to either (a coarse level's block is assembled from its own cell). Throws as
// layered_block_mesh. Implemented with it (src/mesh/layered_block_mesh.cpp), whose steps it shares.
ArrayBlockMesh array_block_mesh(const LayeredBlockOptions& options, const CellLattice& lattice);

// The sites as a full grid of cells: cell (column i, row j) centred on first + (i pitch_x, j pitch_y), holding the
// lattice's sites.
struct SiteGrid {
  Eigen::Vector2d first = Eigen::Vector2d::Zero();  // m, the centre of the cell at column 0, row 0
  double pitch_x = 0, pitch_y = 0;                  // m, > 0
  std::vector<Eigen::Vector2d> sites;               // m, the sites in a cell, from its centre
  // m, from the centre of the last row's cell in each column: the sites of a row above the last row of cells (a
  // hexagonal array of an odd number of rows: the first row of a pair that has no second), in the +y margin strip.
  std::vector<Eigen::Vector2d> top_row_sites;
  // The sites are the cell's four corners, each shared by the cells that meet there: a square array framed from
  // needle to needle, for a reduced model whose symmetry plane runs through a row or column of needles.
  bool sites_on_corners = false;
  int columns = 0, rows = 0;
  // m, >= 0: the block beyond the outermost cells: -x, +x, -y, +y.
  double margin_left = 0, margin_right = 0, margin_bottom = 0, margin_top = 0;
};

struct SiteGridCheck {
  std::optional<SiteGrid> grid;  // empty: the block is not a grid of whole cells, `reason` says why
  std::string reason;
};

// The block's insertion sites as a grid of the lattice's cells, or why the block cannot be assembled from cells: no
// lattice, fewer than two sites, sites that are not every site of every cell of a grid (except a hexagonal array's
// last row of an odd number: half a cell, meshed in the +y margin strip), a cell that leaves the block (a needle on
// the block's edge, where a symmetry plane runs through a row or column; a square array's cells are then framed
// from needle to needle instead, with the needles on their corners, when no circles are to be embedded round the
// needles), or a margin piece thinner than half of size_at_site (its tetrahedra would be flat).
SiteGridCheck site_grid(const LayeredBlockOptions& options, const CellLattice& lattice);

// The block assembled from `cell` (in m, the cell centred on the origin) whose tetrahedra belong to `piece`
// (3 * py + px: px, py = 0 the -x/-y margin, 1 the cell, 2 the +x/+y margin): the cell copied to every cell of
// `grid`, the margin strips along the sides, the corners once. The cell's side faces at +pitch_x/2 (+pitch_y/2) must
// be the faces at -pitch_x/2 (-pitch_y/2) translated by the pitch, node for node (within 1e-7 of the pitch), else
// throws std::logic_error. Nodes are numbered in the order the tetrahedra first use them, row of cells by row.
TetMesh replicated_cells(const TetMesh& cell, const std::vector<int>& piece, const SiteGrid& grid);

}  // namespace needlekit::mesh
