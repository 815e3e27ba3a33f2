// A patch case's body surface and summary as `needlekit patch` and `needlekit serve`'s patch jobs present them: one
// place for the sequence, so that the two cannot drift apart.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/io/mesh_attribution.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/patch/fit_and_evaluate.hpp"

namespace needlekit::io {

struct PatchSurface {
  geometry::SurfaceMesh surface;            // in metres, facing outwards
  std::vector<std::string> warnings;        // a surface turned outwards, implausible scales, no attribution
  std::optional<MeshAttribution> attribution;
};

// Reads the case's mesh at its unit (geometry::read_body_surface) with its warnings. Throws IoError / InvalidInput.
PatchSurface read_patch_surface(const PatchCase& c);
// The same warnings for the case's body surface read already (`needlekit serve` keeps the body it last read).
std::vector<std::string> patch_surface_warnings(const PatchCase& c, const geometry::BodySurface& body);

// patch_summary_json() of the fit, with the springs measured along the surface when the fit measured them
// ("spring_geodesic_strain", "spring_geodesics_not_converged") and `warnings` as "notes".
nlohmann::json patch_case_summary(const PatchCase& c, const patch::FitAndEvaluateResult& result,
                                  const std::vector<std::string>& warnings);

}  // namespace needlekit::io
