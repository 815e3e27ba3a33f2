// Rigid patch fitting (dissertation §6.4.1, the control group): the flat patch is lowered along the approach
// direction until it first touches the surface — at a node, or at a surface vertex under its w × w footprint (the
// substrate is a plate); it does not deform and every needle stays normal to the patch (along the approach).
// `first_node` is the node nearest to the surface along the approach.
#pragma once
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/patch/fitted_patch.hpp"

namespace needlekit::patch {

// Nodes whose approach ray misses the surface are named in `affected_nodes` with status MissesSurface when no
// node hits (the patch is then left at its start height) and BoundaryReached when only some miss (the patch hangs
// over the surface's edge).
FittedPatch rigid_fit(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame);

}  // namespace needlekit::patch
