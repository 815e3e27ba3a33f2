// Private to the Gmsh module (src/mesh/gmsh/): the steps that the whole block (layered_block_gmsh.cpp) and the array
// cell (cell_block_gmsh.cpp) share: the size fields, the meshing options, the interface algorithms and the conversion
// of the current Gmsh model to a TetMesh. They act on the current Gmsh model (inside a GmshSession).
#pragma once
#include <utility>
#include <vector>

#include "../gmsh_module.hpp"

namespace needlekit::mesh::detail {

constexpr double kModelUnit = 1e-6;  // m per Gmsh model unit (um)

// The layers of a block (model units).
struct LayerVolumes {
  std::vector<int> volume_of_layer;  // Gmsh volume tag of each layer (whole block only)
  std::vector<double> tops;          // z of each layer's top
  double height = 0;                 // the block's
};

// A Gmsh volume and the layer its tetrahedra belong to.
struct VolumeLayer {
  int volume = 0;
  int layer = 0;
};

// The volumes that the boxes (dim, tag) become when OpenCASCADE fragments them into one conforming model, one per
// box, in order (a box split into several entities is a logic_error).
std::vector<int> fragmented_volumes(const std::vector<std::pair<int, int>>& boxes);

// The current model's tetrahedra of `volumes`, in that order, as a TetMesh: the nodes they use, in Gmsh's order,
// converted to m.
TetMesh gmsh_tet_mesh(const std::vector<TissueLayer>& layers, const std::vector<VolumeLayer>& volumes);

// Alternates the interfaces' and the bottom's surface algorithms (Delaunay, Frontal-Delaunay) so that a thin
// layer's two faces do not carry the same triangulation; every face at an interface's z within |x| <= w/2,
// |y| <= l/2 (model units).
void alternate_interface_algorithms(const LayerVolumes& volumes, double w, double l, double eps);

// The background size field: size_at_site within refinement_radius of `site_points` (Gmsh point tags), growing at
// size_gradient to size_far, and capped in each thin layer; w and l (model units) bound the block in x and y.
void set_size_fields(const LayeredBlockOptions& options, const std::vector<TissueLayer>& layers,
                     const LayerVolumes& volumes, const std::vector<int>& site_points, double w, double l, double u);

// The meshing algorithms (Frontal-Delaunay surfaces, Delaunay 3D, optimised) on `threads_option` threads (0: one).
void set_mesh_options(int threads_option);

}  // namespace needlekit::mesh::detail
