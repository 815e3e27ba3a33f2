// Validation of tetrahedral meshes (dissertation §3.3.1, §3.3.3): right-hand orientation (Fig 3.2), inverted and
// degenerate elements with their indices, and element quality.
#pragma once
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/tet_mesh.hpp"

namespace needlekit::mesh {

// Fig 3.2's right-hand rule: ((p2 - p1) x (p3 - p1)) . (p4 - p1) / 6, positive when p4 lies on the side of the
// normal of the counter-clockwise triangle (p1, p2, p3).
double signed_volume(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3,
                     const Eigen::Vector3d& p4);

// The shape measure gamma = 3 r_in / R_circ (inscribed over circumscribed sphere radius, 1 for a regular
// tetrahedron, 0 for a flat one); independent of orientation and scale.
double tet_quality(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3,
                   const Eigen::Vector3d& p4);

struct TetMeshCheckOptions {
  double degenerate_quality = 1e-4;  // gamma, [0, 1): elements with a lower quality (flat, needle or cap shaped,
                                     // zero volume) are degenerate
};

struct TetMeshCheck {
  std::vector<int> inverted;    // elements with negative signed volume (left-handed), ascending
  std::vector<int> degenerate;  // elements with quality < degenerate_quality, ascending
  std::vector<double> quality;  // gamma per element
  double min_quality = 0;
  double mean_quality = 0;
  double volume = 0;            // m^3, sum of |signed volume|
  bool valid() const { return inverted.empty() && degenerate.empty(); }
};

// Checks every element. Throws InvalidInput (naming `where`) only for structural errors: a node index out of range,
// a repeated node in an element, or a tet_layer that does not match tets/layers.
TetMeshCheck tet_mesh_check(const TetMesh& mesh, const TetMeshCheckOptions& options = {},
                            std::string_view where = "mesh");

// Throws InvalidInput naming `where`, the number and the first indices of inverted and of degenerate elements (and
// the structural errors of tet_mesh_check). Use it on user meshes.
void validate(const TetMesh& mesh, std::string_view where = "mesh", const TetMeshCheckOptions& options = {});

// Makes every element right-handed by swapping its 2nd and 3rd nodes where the signed volume is negative; returns
// the number of elements swapped.
int reoriented_count(TetMesh& mesh);

// Element count and minimum and mean gamma of each layer (the mesh's layers, in order).
std::vector<LayerQuality> layer_quality(const TetMesh& mesh);

}  // namespace needlekit::mesh
