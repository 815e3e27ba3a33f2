// Flexible patch fitting by node sweeping (dissertation §5.7, Algorithms 5.1–5.3, Eqs 5.13–5.15).
//
// Alg 5.1: the first node is projected onto the surface along the approach direction; then, breadth first, every
// unmapped neighbour of the active node is mapped — axial neighbours by perpendicular mapping (Alg 5.2), diagonal
// ones by diagonal mapping (§5.7.2) — and queued. Both mappings walk from the active node's surface point over the
// surface by the spring's rest length along the cutting plane spanned by the spring's original direction d and the
// surface normal (Alg 5.3, geodesic traverse across adjacent triangles; notes: the plane through d and the normal
// gives a straightest path). That point N_int is where the node would lie if the patch conformed completely.
//
// Energy limit (Eqs 5.13–5.15). Eq 5.15 as printed is not dimensionally consistent (notes); implemented instead is
// a cap on every spring's energy, ½·K·ΔL² <= E_cri (Eqs 5.13, 5.14 per spring): the node is placed at
//   N' = N + λ·(N_int − N),
// where N is its undeformed position relative to the active node (the patch locally rigid) and λ in [0, 1] is the
// largest value for which every spring joining the node to an already mapped node stays at or under E_cri. Large
// E_cri: λ = 1, the patch conforms; E_cri → 0: λ = 0, the patch keeps its flat shape (the rigid patch through the
// first node). A node that would end beneath the surface is put back onto it (the surface is impenetrable). Unlike
// Alg 5.2, the cap is applied to every node (also the edge nodes in line with the first one), so that E_cri → 0
// gives the rigid patch.
#pragma once
#include <functional>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/patch/fitted_patch.hpp"

namespace needlekit::patch {

enum class FirstNode {
  FirstContact,  // the node that touches first when the flat patch is lowered (the rigid fit's contact node)
  Corner,        // N(0,0), the corner of minimum U and V (Alg 5.1 as printed)
};
inline constexpr EnumTable<FirstNode, 2> kFirstNodeNames{{
    {FirstNode::FirstContact, "first-contact", "the node that touches first when the flat patch is lowered"},
    {FirstNode::Corner, "corner", "N(0,0), the corner of minimum U and V (Alg 5.1 as printed)"},
}};

enum class WalkMethod {
  CuttingPlane,  // Alg 5.3: geometry::cutting_plane_trace, the surface cut by the plane through d and the normal
  Unfolding,     // geometry::straightest_geodesic: edge unfolding (Polthier & Schmies), the exact geodesic on
                 // developable surfaces such as the cylinder
};
inline constexpr EnumTable<WalkMethod, 2> kWalkMethodNames{{
    {WalkMethod::CuttingPlane, "cutting-plane", "Alg 5.3: the surface cut by the plane through the direction and "
                                                "the normal"},
    {WalkMethod::Unfolding, "unfolding", "straightest geodesic by edge unfolding (exact on developable surfaces)"},
}};

struct FlexibleFitOptions {
  double max_spring_energy = 5e-5;     // J, (0, inf]: E_cri per spring (0.05 mJ); inf = conform completely
  FirstNode first_node = FirstNode::FirstContact;
  int cap_samples = 32;                // [2, 10000]: samples of λ before bisection in the energy cap
  WalkMethod walk = WalkMethod::CuttingPlane;  // how the geodesic traverse crosses triangle edges
  // Called after each node is mapped (Alg 5.1's loop) with the fraction of the patch's nodes mapped, in (0, 1]. Return
  // false to stop: flexible_fit throws needlekit::Interrupted. May be empty.
  std::function<bool(double)> progress;
};

// Throws InvalidInput for a non-positive E_cri or cap_samples out of range. Traverses that reach the surface's
// boundary or a degenerate triangle stop there: status BoundaryReached / DegenerateSurface naming the nodes.
FittedPatch flexible_fit(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                         const FlexibleFitOptions& options = {});

}  // namespace needlekit::patch
