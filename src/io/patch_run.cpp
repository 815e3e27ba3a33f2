#include "needlekit/io/patch_run.hpp"

#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/patch_writers.hpp"
#include "needlekit/io/scale_warnings.hpp"

namespace needlekit::io {

std::vector<std::string> patch_surface_warnings(const PatchCase& c, const geometry::BodySurface& body) {
  std::vector<std::string> warnings = patch_scale_warnings(body.surface.mesh(), patch::patch_design(c.design));
  if (body.flipped) warnings.insert(warnings.begin(), body.note);
  if (!mesh_attribution(c.mesh)) warnings.push_back(missing_attribution_warning(c.mesh));
  return warnings;
}

PatchSurface read_patch_surface(const PatchCase& c) {
  geometry::BodySurface body = geometry::read_body_surface(c.mesh, c.mesh_unit);
  std::vector<std::string> warnings = patch_surface_warnings(c, body);
  return {std::move(body.surface), std::move(warnings), mesh_attribution(c.mesh)};
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
