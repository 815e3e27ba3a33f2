// The 3D view of a patch fit (docs/views.md), in the data format of io/indentation_view.hpp: the body surface near
// the patch, the fitted patch (springs as lines) and every needle as a base-to-tip segment with its row of numbers
// (forces, critical loads and their margins, angle, penetration, performance index, status), which the viewer
// colours by a chosen column (Fig 6.24) and shows when the needle is clicked.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"

namespace needlekit::io {

// {"format": "needlekit-view/1", "kind": "patch", "name", "title", "steps": [one], "surface": {"vertices", "indices",
// "positions", "fields": []}, "lines": {"positions"}, "needles": {"segments", "radius_m", "table": {"columns",
// "rows"}}}. The surface: the triangles with a vertex within the patch's diagonal of its centre.
nlohmann::json patch_view(const std::string& name, const geometry::SurfaceMesh& surface,
                          const patch::PatchDesign& design, const patch::FittedPatch& fit,
                          const patch::PatchEvaluation& evaluation);

}  // namespace needlekit::io
