// Rezoning a deformed tissue mesh (issue 35 item 3): the tissue as the needles have deformed it is meshed anew, and
// the new mesh is given a reference configuration and a displacement so that a total-Lagrangian solver continues
// from it.
//
// 1. The crushed region (the old tetrahedra whose J = det F is below RezoneOptions::volume_ratio, with a few rings of
//    neighbours; or the whole tissue) is taken out. Its deformed boundary is kept as it is, node for node, and its
//    inside is filled again by Delaunay 3D (Gmsh), with the old mesh's local element size: well-shaped tetrahedra
//    replace the crushed ones under the tips, and the tetrahedra outside the region stay as they were.
// 2. Each new node inside is located in the old deformed mesh (mesh/tet_locator.hpp) and carried back to the
//    reference configuration with the old element's linear shape functions, X = sum_i N_i(x) X_i: the new element's
//    deformation gradient is then the old mapping's average over it (for a linear old mapping, exactly the old one).
//    The old nodes that stay (every boundary node among them) keep their reference positions and displacements
//    exactly, so the top surface, the symmetry planes and the fixed faces are where they were (old_node maps them).
//    Where the old mapping bends sharply within a new tetrahedron (round a needle's rim, or where the surface layer
//    is sheared along a bevel by more than an element), the carried-back tetrahedron can be flat or inverted:
//     - a tetrahedron of four boundary nodes across a bend of the surface is split along its chord under the bend;
//     - the inner nodes of the others are smoothed in the deformed state and carried back again;
//     - what remains takes its own reference shape (OwnReference) from the old deformation gradient at its
//       deformed centroid, so that its F at the transfer is the old element's.
// 3. Each new tetrahedron takes the layer of the old tetrahedron that contains its deformed centroid. A layer
//    interface is therefore resolved to the new elements' size, not kept as a surface.
//
// This is the rezone-and-remap step of an arbitrary Lagrangian-Eulerian method done in the total-Lagrangian frame
// (Belytschko, Liu & Moran, Nonlinear Finite Elements, 2000, §7.4: rezone, then remap the state by interpolation);
// the hyperelastic tissue carries no internal variables, so its state is its reference position.
#pragma once
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

struct RezoneOptions {
  // Only the old tetrahedra whose J = det F is below volume_ratio, grown by `rings` rings of tetrahedra that share a
  // node, are meshed anew; the others are kept as they are. 0, or no tetrahedron below it: the whole tissue.
  double volume_ratio = 0;
  int rings = 3;
  // m, the new tetrahedra's edge length at a point of the deformed tissue; unset: the old mesh's own, the mean edge
  // length in the deformed state interpolated from its nodes (scaled so that the element count stays about the same)
  std::function<double(const Eigen::Vector3d&)> size;
};

struct RezonedMesh {
  TetMesh mesh;                               // the new reference mesh (nodes pulled back; the old layers)
  std::vector<Eigen::Vector3d> displacement;  // m, per new node: deformed minus reference position
  std::vector<int> old_node;                  // per new node: the old node it is, or -1
  int kept_nodes = 0;                         // the old nodes still in use (every boundary node among them),
                                              // numbered first and in their old order
};

// Throws InvalidInput when `displacement` does not have one vector per node, and std::runtime_error when, with every
// size and region tried, Gmsh cannot fill the deformed boundary (it touches itself) or a new tetrahedron has no
// shape (inverted carried back, and the old deformation gradient where it is inverted too).
RezonedMesh rezoned_mesh(const TetMesh& reference, const std::vector<Eigen::Vector3d>& displacement,
                         const RezoneOptions& options = {});

}  // namespace needlekit::mesh
