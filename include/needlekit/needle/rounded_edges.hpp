// A needle with rounded edges, as its core: real microneedle edges are not sharp (moulded and etched tips have edge
// radii of a few micrometres). The needle whose every convex edge is rounded with radius ρ is the set of points within
// ρ of the needle eroded by ρ (every face, wall and the bore moved inwards by ρ): a morphological opening, which keeps
// the flat faces, the walls and the outline where they were. The FE's surface contact measures distances to the core's
// mesh and subtracts ρ (fem::Indenter::edge_radius).
#pragma once
#include <string_view>

#include "needlekit/needle/needle_geometry.hpp"

namespace needlekit::needle {

struct ErodedNeedle {
  NeedleGeometry core;     // the eroded needle, in its own needle frame (base at z = 0, tip at z = core.length)
  double base_offset = 0;  // m, <= 0: z of the core's base in the needle's frame; its tip is at length - ρ there
};

// The largest edge radius a needle can have (exclusive): half the tip's diameter (a bevel: half its tip face's
// sagitta), and for a hollow needle a quarter of the wall between bore and tip, (D1 - D3) / 4.
double max_edge_radius(const NeedleGeometry& needle);

// A typical moulded or etched microneedle's edge radius, m, the default of FE cases with surface contact.
inline constexpr double kTypicalEdgeRadius = 2e-6;
// kTypicalEdgeRadius, or half of max_edge_radius for a needle too fine for it.
double default_edge_radius(const NeedleGeometry& needle);

// The core of `needle` with edge radius `radius` in [0, max_edge_radius). Cylinder: D - 2ρ, length L - ρ. Cone: the
// wall moved in by ρ along its normal, i.e. the radius by ρ·√(1 + k²) with k = (D2 - D1) / 2L, and the tip down by ρ.
// Bevel: the side wall in by ρ, the bevel plane along its normal by ρ and the tip face down by ρ; the moved plane
// meets the smaller circle a little below the base, so the core's base is there (base_offset < 0: a part of the needle
// far from the tissue). A bore grows by 2ρ. Throws InvalidInput naming `where`.edge_radius outside the range.
ErodedNeedle eroded_needle(const NeedleGeometry& needle, double radius, std::string_view where = "needle");

}  // namespace needlekit::needle
