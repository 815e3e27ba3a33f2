// One entry point for the three ways of fitting a patch: rigid (§6.4.1), flexible by node sweeping (§5.7,
// Alg 5.1–5.3) and the static equilibrium (beyond the dissertation).
#pragma once
#include <string_view>

#include "needlekit/core/enum_table.hpp"
#include "needlekit/patch/equilibrium_fit.hpp"
#include "needlekit/patch/flexible_fit.hpp"
#include "needlekit/patch/rigid_fit.hpp"

namespace needlekit::patch {

enum class PatchKind { Rigid, Flexible, Equilibrium };
inline constexpr EnumTable<PatchKind, 3> kPatchKindNames{{
    {PatchKind::Rigid, "rigid", "a flat patch lowered until its first needle touches (§6.4.1)"},
    {PatchKind::Flexible, "flexible", "node sweeping: each node follows the surface up to the spring-energy cap E_cri "
                                      "(Alg 5.1-5.3)"},
    {PatchKind::Equilibrium, "equilibrium", "the static equilibrium of the springs under a load per node (beyond the "
                                            "dissertation)"},
}};
std::string_view to_string(PatchKind kind);
// A name of kPatchKindNames; throws InvalidInput naming `what` otherwise.
PatchKind patch_kind_from_string(std::string_view text, std::string_view what = "patch.kind");

struct FitOptions {
  PatchKind kind = PatchKind::Flexible;
  FlexibleFitOptions flexible;        // used when kind == Flexible
  EquilibriumFitOptions equilibrium;  // used when kind == Equilibrium
};

FittedPatch fit_patch(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                      const FitOptions& options = {});

}  // namespace needlekit::patch
