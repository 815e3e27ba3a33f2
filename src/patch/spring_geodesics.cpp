#include "needlekit/patch/spring_geodesics.hpp"

#include <cmath>
#include <limits>

#include "needlekit/geometry/geodesic_distance.hpp"

namespace needlekit::patch {

SpringGeodesics spring_geodesics(const geometry::SurfaceMesh& surface, const PatchDesign& design,
                                 const FittedPatch& fit) {
  SpringGeodesics result;
  std::vector<geometry::SurfaceLocation> location(design.node_count());
  for (int k = 0; k < design.node_count(); ++k) location[k] = geometry::surface_location(surface.closest_point(fit.positions[k]));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> magnitudes;
  geometry::GeodesicDistanceOptions options;
  options.graph_fallback = false;  // nearby points: the shot towards the target converges
  for (const Spring& spring : design.springs) {
    const geometry::GeodesicDistance g = geometry::geodesic_distance(surface, location[spring.a], location[spring.b], options);
    if (g.status != geometry::DistanceStatus::Converged) {
      ++result.not_converged;
      result.geodesic_length.push_back(nan);
      result.strain.push_back(nan);
      continue;
    }
    const double strain = (g.distance - spring.rest_length) / spring.rest_length;
    result.geodesic_length.push_back(g.distance);
    result.strain.push_back(strain);
    magnitudes.push_back(std::abs(strain));
  }
  result.strain_abs = statistics(magnitudes);
  return result;
}

}  // namespace needlekit::patch
