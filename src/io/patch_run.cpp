#include "needlekit/io/patch_run.hpp"

#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/patch_writers.hpp"
#include "needlekit/io/scale_warnings.hpp"

namespace needlekit::io {

namespace {

// The body's warnings; `attributed`: the mesh has its attribution (mesh_attribution, a file read, done once).
std::vector<std::string> surface_warnings(const PatchCase& c, const geometry::BodySurface& body, bool attributed) {
  std::vector<std::string> warnings = patch_scale_warnings(body.surface.mesh(), patch::patch_design(c.design));
  if (body.flipped) warnings.insert(warnings.begin(), body.note);
  if (!attributed) warnings.push_back(missing_attribution_warning(c.mesh));
  return warnings;
}

}  // namespace

std::vector<std::string> patch_surface_warnings(const PatchCase& c, const geometry::BodySurface& body) {
  return surface_warnings(c, body, mesh_attribution(c.mesh).has_value());
}

PatchSurface read_patch_surface(const PatchCase& c) {
  geometry::BodySurface body = geometry::read_body_surface(c.mesh, c.mesh_unit);
  std::optional<MeshAttribution> attribution = mesh_attribution(c.mesh);
  std::vector<std::string> warnings = surface_warnings(c, body, attribution.has_value());
  return {std::move(body.surface), std::move(warnings), std::move(attribution)};
}

nlohmann::json patch_case_summary(const PatchCase& c, const patch::FitAndEvaluateResult& r,
                                  const std::vector<std::string>& warnings) {
  nlohmann::json summary = patch_summary_json(r.design, c.fit, r.fit, r.evaluation, r.fit_seconds * 1e3);
  // Beyond the dissertation: the springs measured along the surface (exact geodesic distances).
  if (r.geodesics) {
    summary["spring_geodesic_strain"] =
        r.geodesics->strain_abs.count == 0
            ? nlohmann::json(nullptr)
            : nlohmann::json{{"max", r.geodesics->strain_abs.max}, {"mean", r.geodesics->strain_abs.mean}};
    summary["spring_geodesics_not_converged"] = r.geodesics->not_converged;
  }
  summary["notes"] = warnings;
  return summary;
}

}  // namespace needlekit::io
