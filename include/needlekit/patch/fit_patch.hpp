// One entry point for the three ways of fitting a patch: rigid (§6.4.1), flexible by node sweeping (§5.7,
// Alg 5.1–5.3) and the static equilibrium (beyond the dissertation).
#pragma once
#include <string_view>

#include "needlekit/patch/equilibrium_fit.hpp"
#include "needlekit/patch/flexible_fit.hpp"
#include "needlekit/patch/rigid_fit.hpp"

namespace needlekit::patch {

enum class PatchKind { Rigid, Flexible, Equilibrium };
std::string_view to_string(PatchKind kind);
// "rigid", "flexible" or "equilibrium"; throws InvalidInput naming `what` otherwise.
PatchKind patch_kind_from_string(std::string_view text, std::string_view what = "patch.kind");

struct FitOptions {
  PatchKind kind = PatchKind::Flexible;
  FlexibleFitOptions flexible;        // used when kind == Flexible
  EquilibriumFitOptions equilibrium;  // used when kind == Equilibrium
};

FittedPatch fit_patch(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                      const FitOptions& options = {});

}  // namespace needlekit::patch
