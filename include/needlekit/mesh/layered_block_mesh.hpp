// A parametric layered tissue block (dissertation §3.3, default 3000 x 3000 x 1150 um: stratum corneum 20 um,
// epidermis to 160 um, dermis below) meshed into linear tetrahedra with the Gmsh C++ API: conforming layer
// interfaces and size fields refined around each insertion site. Gmsh stays in the Gmsh module
// (src/mesh/gmsh/, opened on the first call: src/mesh/gmsh_module.hpp).
#pragma once
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "needlekit/core/limits.hpp"
#include "needlekit/mesh/tet_mesh.hpp"
#include "needlekit/mesh/coarse_level.hpp"

namespace needlekit::mesh {

struct LayeredBlockOptions {
  double width = 3000e-6;               // m, block extent in x, > 0 (centred on x = 0)
  double length = 3000e-6;              // m, block extent in y, > 0 (centred on y = 0)
  std::vector<TissueLayer> layers;      // top to bottom; total thickness = block height; empty: skin_layers()
  std::vector<Eigen::Vector2d> insertion_sites{Eigen::Vector2d::Zero()};  // m, (x, y) on the top surface z = 0
  double size_at_site = 20e-6;          // m, target element size at each insertion site, > 0
  double refinement_radius = 300e-6;    // m, radius around a site where the size is size_at_site, > 0
  double size_far = 250e-6;             // m, element size far from the sites, >= size_at_site
  int threads = 0;                      // Gmsh threads, >= 0: 0 = one thread (the mesh is then the same, bit for
                                        // bit, in every run); N > 1 meshes surfaces on N threads, whose meshes
                                        // differ between runs in their last bits
  double size_gradient = 0.3;           // 1, (0, inf): growth of the element size per unit distance outside the
                                        // refinement radius and outside thin layers (0.3: 30 um per 100 um)
  double thin_layer_size_factor = 2.0;  // 1, [0, inf): the element size inside a layer is capped at this times its
                                        // thickness so that thin layers (the stratum corneum) keep well-shaped
                                        // elements; 0 = no cap
  double site_circle_radius = 0;        // m, >= 0: a circle of this radius around each site is embedded in the top
                                        // surface, so that mesh nodes lie on a flat punch's edge; 0 = none
  bool split = false;                   // mesh at twice the sizes (and size gradient), then split every tet into
                                        // eight (refine_uniformly): about the same elements, and the coarse level
                                        // that lets the FE solver use its two-grid solver (fast on large meshes)
  bool coarse_level = false;            // also return a coarse level for the FE solver's two-grid solver: with
                                        // split the mesh it was split from; else the block meshed again at
                                        // coarse_size_factor times the sizes, with this mesh's nodes interpolated in
                                        // it (interpolating_coarse_level)
  double coarse_size_factor = 3.0;      // 1, > 1: the coarse level's sizes (and size gradient) over this mesh's,
                                        // coarse_level without split only (a split's parent is at twice the sizes).
                                        // The non-nested coarse operator is dense (~70 entries per column), so its
                                        // factor's solves, one or two per CG iteration, grow faster than the fine
                                        // products: on the 351k skin block 3 took 0.25 s per Newton iteration
                                        // (332 CG iterations, factor 6.7e6 entries) against 0.32 s with 2 (211,
                                        // 3.1e7), 0.29 s with 2.5 and 0.34 s with 4; on the 119k block 2 and 3 are
                                        // even; on the §6.2 sharp bevel (nodal average, two cycles per iteration)
                                        // 3 beat 2 and 4 (BENCHMARKS.md, ninth and eleventh sessions)
  double max_tetrahedra = limits::kMaxTetrahedra;  // > 0: a block whose estimated tetrahedron count
                                        // (estimated_tetrahedra, tet_count_estimate.hpp) exceeds this is refused
                                        // before meshing; the case file's [mesh] max_tetrahedra
};

struct LayerQuality {
  std::string name;
  int tets = 0;
  double min_quality = 0;   // gamma = 3 r_in / R_circ (inscribed / circumscribed radius ratio, normalised to 1 for a
                            // regular tet; mesh::tet_quality)
  double mean_quality = 0;
};

struct LayeredBlockResult {
  TetMesh mesh;                     // layer assignment by the geometric volume (physical group) of each element
  std::vector<LayerQuality> quality;  // one per layer
  std::optional<CoarseLevel> coarse;  // with split or coarse_level: see LayeredBlockOptions::coarse_level
  double mesh_seconds = 0;
};

// Meshes the block. Throws InvalidInput for non-positive sizes or thicknesses (naming the field), a site outside the
// top surface, invalid layers or an estimated tetrahedron count above max_tetrahedra (before any meshing). With
// threads = 0 the mesh depends only on the options: the same node coordinates, bit for bit, in every run, whatever
// the process's memory layout, file names or environment.
LayeredBlockResult layered_block_mesh(const LayeredBlockOptions& options);

}  // namespace needlekit::mesh
