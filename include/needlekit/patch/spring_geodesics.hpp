// Beyond the dissertation: how far the fitted patch's springs are from their rest lengths when measured along the
// surface. Each node is projected onto the surface (closest point) and the exact geodesic distance between the two
// ends of every spring (geometry::geodesic_distance, straightest-geodesic shooting) is compared with the rest
// length: the node-sweeping heuristic places each node at the rest length from one neighbour only, so the others
// show its error; the equilibrium fit trades these errors against the springs' energy.
#pragma once
#include <vector>

#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/patch/fitted_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"

namespace needlekit::patch {

struct SpringGeodesics {
  std::vector<double> geodesic_length;  // m per spring (NaN when the distance did not converge)
  std::vector<double> strain;           // (geodesic − rest)/rest per spring (NaN when not converged)
  Statistics strain_abs;                // of |strain| over the converged springs
  int not_converged = 0;
};

SpringGeodesics spring_geodesics(const geometry::SurfaceMesh& surface, const PatchDesign& design,
                                 const FittedPatch& fit);

}  // namespace needlekit::patch
