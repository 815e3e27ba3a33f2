// Plausibility of the scales of a run's inputs, checked where they enter (core/plausible_scale.hpp): each returns
// warnings that name the value, the plausible range and the likely unit mistake; the commands put them in the
// result's "notes" and on the terminal. The plausible ranges are declared here, once:
//   a microneedle's length                    20 um to 5 mm
//   a body surface mesh's largest extent      1 cm to 3 m
//   a needle mesh across                      at most the tissue block's width and length
//   a needle                                  at most as long as the tissue block is high
//   a patch                                   at least the body mesh's median edge
#pragma once
#include <string>
#include <vector>

#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/needle/needle_geometry.hpp"
#include "needlekit/patch/patch_design.hpp"

namespace needlekit::io {

inline constexpr double kPlausibleNeedleLength[2] = {20e-6, 5e-3};  // m
inline constexpr double kPlausibleBodyExtent[2] = {1e-2, 3.0};       // m

// The needle's length.
std::vector<std::string> needle_scale_warnings(const needle::NeedleGeometry& needle);
// A body surface (in m): its largest bounding-box extent; `unit_key` names the key that sets its unit.
std::vector<std::string> surface_scale_warnings(const geometry::TriangleMesh& surface, std::string_view unit_key);
// A patch on a body surface: the surface and the needle as above, and the patch against the surface's median edge.
std::vector<std::string> patch_scale_warnings(const geometry::TriangleMesh& surface, const patch::PatchDesign& design);
// An indentation case: the needle's length, a needle mesh wider than the block or a needle longer than the block is
// high (a needle STL in um declared as mm), a steep angle, an array's block meshed whole, and a reduced array model
// whose needle is not its own mirror image across a symmetry plane (insertion::off_mirror_plane).
std::vector<std::string> indentation_scale_warnings(const insertion::IndentationCase& indentation_case);

}  // namespace needlekit::io
