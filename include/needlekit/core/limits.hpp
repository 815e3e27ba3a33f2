// The work limits, declared once. A run whose estimated size exceeds one is refused before any work starts, with the
// estimate and the key or option that raises the limit (README "Limits"): no input makes the tool mesh, allocate or
// enumerate for minutes or until memory runs out because of a typo in a size or a step.
#pragma once
#include <cstdint>

namespace needlekit::limits {

// Tetrahedra of a meshed tissue block, estimated from the block and mesh sizes (mesh::estimated_tetrahedra).
// Override: [mesh] max_tetrahedra. 5e7 tetrahedra take about 30 GB to solve with linear elements.
inline constexpr double kMaxTetrahedra = 5e7;

// Grid points `optimize` enumerates without --certified (about 100 s at the benchmarked 1e8 points/s).
// Override: optimize --max-grid-points.
inline constexpr std::uint64_t kMaxBruteForcePoints = 10'000'000'000ULL;

// Memory the design optimizer allocates for its grid (values, per-(D1, D2) and per-(D1, D2, D3) tables).
// Override: optimize --max-memory-gib.
inline constexpr double kMaxOptimizerMemoryBytes = 4.0 * (1ULL << 30);

// Counts a case file may ask for (refused above, in the reader): each load step is a full FE solve, each needle
// mesh segment multiplies the contact work.
inline constexpr int kMaxLoadSteps = 10'000;          // [loading] steps
inline constexpr int kMaxCurveSamples = 1'000'000;    // [post_puncture] samples
inline constexpr int kMaxNeedleSegments = 4'096;      // [needle] segments and axial_segments

}  // namespace needlekit::limits
