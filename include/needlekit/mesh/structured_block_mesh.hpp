// A structured tetrahedral mesh of a box (for verification tests and quick runs without Gmsh): nx x ny x nz hexes,
// each split into 5 or 6 right-handed tetrahedra, with optional geometric grading of the spacing towards a point of
// the top surface. Frame of tet_mesh.hpp: the box spans [-width/2, width/2] x [-length/2, length/2] x [-height, 0].
#pragma once
#include <Eigen/Core>

#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

struct StructuredBlockOptions {
  double width = 1e-3;     // m, x extent, > 0
  double length = 1e-3;    // m, y extent, > 0
  double height = 1e-3;    // m, z extent, > 0
  int nx = 8;              // hexes along x, >= 1
  int ny = 8;              // hexes along y, >= 1
  int nz = 8;              // hexes along z, >= 1
  int tets_per_hex = 6;    // 5 or 6 (5: alternating pattern so faces conform)
  Eigen::Vector2d focus = Eigen::Vector2d::Zero();  // m, (x, y) on the top surface that grading refines towards
  double grading = 1.0;    // >= 1: ratio of the largest to the smallest spacing along each axis (1 = uniform);
                           // spacing grows geometrically away from the focus in x and y, and downwards in z
  TissueLayer material{"block", 0.0, 1e6, 0.4};  // one layer (thickness set to height)
  // Uniform core (replaces `grading` when > 0): `core_cells` equal cells over `core_half_width` on each side of the
  // focus in x and y and below the top in z; outside the core the spacing grows geometrically from the core's
  // spacing to the block's faces. nx, ny need > 2 * core_cells and nz > core_cells.
  int core_cells = 0;            // >= 0, 0 = no core
  double core_half_width = 0;    // m, > 0 when core_cells > 0
  bool round_core = false;       // map the core's concentric squares (about the focus) onto circles, blending back
                                 // to the grid by twice the core half-width: nodes then lie on the circle of radius
                                 // core_half_width (a resolved flat-punch edge)
};

// Throws InvalidInput naming the field for non-positive sizes, counts < 1, tets_per_hex not 5 or 6, grading < 1, a
// focus outside the top face.
TetMesh structured_block_mesh(const StructuredBlockOptions& options);

}  // namespace needlekit::mesh
