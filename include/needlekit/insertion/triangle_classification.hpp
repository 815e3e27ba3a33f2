// Classification of a needle's surface triangles against the insertion direction (dissertation §3.6.1-3.6.2,
// Figs 3.6-3.7): which triangles push tissue away when the needle moves through punctured tissue.
//
//   group 1 (side):  the normal is (nearly) perpendicular to the insertion direction d; tissue slides over it.
//   group 2 (front): the normal points along d (n·d > 0); split into
//                      α: n parallel to d (the flat tip face; uniform load, Eq 3.18),
//                      β: n deviates from d but still points along the insertion path (a slope; triangular load,
//                         Algorithm 3.1).
//   group 3 (back):  the normal points against d (n·d < 0); no contact with tissue.
// Two more outcomes remove group-2 triangles from the load:
//   channel:  a triangle of an internal structure (the bore of a hollow needle), which "does not affect the
//             insertion force" (§3.6.1). Detected as a triangle whose outward normal points toward the needle axis
//             (n·ê_ρ < 0) and which is either inside `bore_radius` of the axis or, when a SurfaceMesh is supplied,
//             not visible from outside: the ray from its centroid along its outward normal hits the needle again.
//   occluded: the optional test for jagged needles (§3.6.1): a ray cast from a vertex along d must not hit the needle;
//             a group-2 triangle is occluded when the rays from all three of its vertices hit the needle.
//
// Frame: the needle frame of needle_geometry.hpp (axis z, tip at the largest z), so that d = +z by default.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"

namespace needlekit::geometry {
class SurfaceMesh;
}

namespace needlekit::insertion {

enum class TriangleClass {
  Side,      // group 1
  Alpha,     // group 2, α
  Beta,      // group 2, β
  Back,      // group 3
  Channel,   // group 2 (or 1) on the bore / an internal structure: excluded
  Occluded,  // group 2 hidden behind other needle material along d: excluded
};
inline constexpr EnumTable<TriangleClass, 6> kTriangleClassNames{{
    {TriangleClass::Side, "side", "group 1"},
    {TriangleClass::Alpha, "alpha", "group 2, alpha"},
    {TriangleClass::Beta, "beta", "group 2, beta"},
    {TriangleClass::Back, "back", "group 3"},
    {TriangleClass::Channel, "channel", "group 2 (or 1) on the bore or an internal structure: excluded"},
    {TriangleClass::Occluded, "occluded", "group 2 hidden behind other needle material along d: excluded"},
}};
std::string_view to_string(TriangleClass triangle_class);

struct TriangleClassificationOptions {
  // Insertion direction d, any length > 0 (normalised inside). Default +z: the needle frame's tip direction.
  Eigen::Vector3d insertion_direction = Eigen::Vector3d::UnitZ();
  // rad, [0, π/4]: a triangle is group 1 (side) when its normal is within this angle of perpendicular to d.
  // Default 1° (the needle meshes' side walls are exactly perpendicular; an STL's may be a little off).
  double side_tolerance = 1.0 * 3.14159265358979323846 / 180;
  // rad, [0, π/4]: a group-2 triangle is α when its normal is within this angle of d ("cross product close to
  // zero", §3.6.2). Default 1°.
  double alpha_tolerance = 1.0 * 3.14159265358979323846 / 180;
  // m, >= 0: radius of the needle's channel about its centre axis for the channel test without a SurfaceMesh
  // (inward-facing triangles whose centroid lies within bore_radius·(1 + 1e-6) of the axis are channel). 0: only
  // the visibility test decides (which needs a SurfaceMesh).
  double bore_radius = 0;
  // A point on the needle's centre axis (the axis is parallel to d through it), m. Default: the origin, the axis of
  // the needle frame.
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  // The occlusion test for jagged needles (§3.6.1); needs a SurfaceMesh.
  bool occlusion_test = false;
};

struct TriangleClassification {
  std::vector<TriangleClass> classes;  // one per triangle of the mesh
  std::vector<int> alpha;              // indices of the α-triangles
  std::vector<int> beta;               // indices of the β-triangles
  int side = 0, back = 0, channel = 0, occluded = 0;
  Eigen::Vector3d insertion_direction = Eigen::Vector3d::UnitZ();  // unit
  double alpha_area = 0;               // m², total area of the α-triangles
  double beta_area = 0;                // m², total area of the β-triangles
};

// Throws InvalidInput with a readable reason when the needle mesh is not a closed, outward-oriented surface: empty,
// open (boundary edges), non-manifold edges, inconsistently oriented, or inverted normals (enclosed volume negative:
// "the normals point inward"). `what` names the mesh in messages.
void validate_needle_surface(const geometry::TriangleMesh& needle, std::string_view what = "needle mesh");

// Classifies every triangle. `surface` (the same mesh as a SurfaceMesh, with its AABB tree) is needed for the
// occlusion test and for the visibility part of the channel test; without it the occlusion test throws
// InvalidInput and the channel test uses `bore_radius` only. Validates the mesh first (validate_needle_surface) and
// throws InvalidInput when no triangle faces the insertion direction (no α- or β-triangle is left).
TriangleClassification classify_triangles(const geometry::TriangleMesh& needle,
                                          const TriangleClassificationOptions& options = {},
                                          const geometry::SurfaceMesh* surface = nullptr);

}  // namespace needlekit::insertion
