#include "needlekit/patch/fit_patch.hpp"

#include <fmt/format.h>

#include "needlekit/core/errors.hpp"

namespace needlekit::patch {

std::string_view to_string(PatchKind kind) { return name_of(kPatchKindNames, kind); }

PatchKind patch_kind_from_string(std::string_view text, std::string_view what) {
  return value_of(kPatchKindNames, text, what);
}

FittedPatch fit_patch(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                      const FitOptions& options) {
  switch (options.kind) {
    case PatchKind::Rigid: return rigid_fit(surface, design, frame);
    case PatchKind::Flexible: return flexible_fit(surface, design, frame, options.flexible);
    case PatchKind::Equilibrium: return equilibrium_fit(surface, design, frame, options.equilibrium);
  }
  return rigid_fit(surface, design, frame);
}

}  // namespace needlekit::patch
