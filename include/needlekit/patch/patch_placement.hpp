// Where and how a patch is applied (dissertation §5.7, §6.4.1): the patch centre over a chosen surface point (or
// vertex), a rotation about the approach axis, and the approach direction (−Z as in the dissertation, or against
// the surface normal at the centre). The result is the patch's starting frame: a plane perpendicular to the
// approach, held `approach_height` above the surface point.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string_view>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/geometry/surface_mesh.hpp"

namespace needlekit::patch {

enum class Approach {
  MinusZ,         // the patch moves along −Z (§5.2: "the input force is always in vertical direction")
  SurfaceNormal,  // the patch moves against the surface normal at the centre point
};
inline constexpr EnumTable<Approach, 2> kApproachNames{{
    {Approach::MinusZ, "-z", "the patch moves along -Z (§5.2: the input force is vertical)"},
    {Approach::SurfaceNormal, "normal", "the patch moves against the surface normal at the centre point"},
}};
std::string_view to_string(Approach approach);

struct Placement {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // m: a point on (or near) the surface under the patch centre
  std::optional<int> center_vertex;   // when set, the centre is this mesh vertex and `center` is ignored
  double rotation = 0;                // rad, any: turns the patch's U axis about the patch normal (−approach), right-handed
  Approach approach = Approach::MinusZ;
  double max_center_distance = 1e-3;  // m, (0, inf): how far `center` may lie from the surface
  double approach_height = 0;         // m, >= 0: start height of the patch above the centre point; 0 = the patch's
                                      // diagonal + needle length (the patch comes in from there)
};

struct PatchFrame {
  Eigen::Vector3d surface_point;   // m, the surface point under the patch centre
  int triangle = -1;               // the triangle of `surface_point`
  Eigen::Vector3d approach;        // unit, direction in which the patch moves (needles point this way)
  Eigen::Vector3d u, v;            // unit, the patch axes; u × v = −approach (the patch normal)
  double approach_height = 0;      // m, the start height used
};

// The frame of the patch. Throws InvalidInput when the centre vertex does not exist, the centre point lies more
// than max_center_distance from the surface, or the surface at the centre faces away from the approach.
PatchFrame patch_frame(const geometry::SurfaceMesh& surface, const Placement& placement, double patch_diagonal,
                       double needle_length);

}  // namespace needlekit::patch
