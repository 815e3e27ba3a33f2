#include "needlekit/patch/placement_scan.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>

#include "needlekit/core/errors.hpp"

namespace needlekit::patch {

std::vector<PlacementSummary> placement_scan(const geometry::SurfaceMesh& surface, const PatchDesign& design,
                                             const std::vector<int>& vertices, const PlacementScanOptions& options) {
  std::vector<PlacementSummary> result(vertices.size());
  const double diagonal = std::hypot(design.width_u, design.width_v);
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices.size(), 16), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      PlacementSummary& s = result[i];
      s.vertex = vertices[i];
      Placement placement;
      placement.center_vertex = vertices[i];
      placement.approach = options.approach;
      placement.rotation = options.rotation;
      PatchFrame frame;
      try {
        frame = patch_frame(surface, placement, diagonal, design.needle.length);
      } catch (const InvalidInput&) {
        continue;  // a vertex the approach cannot reach: not placed
      }
      s.placed = true;
      const FittedPatch fit = fit_patch(surface, design, frame, options.fit);
      s.status = fit.status;
      const PatchEvaluation e = evaluate_needles(surface, design, fit, options.evaluation);
      s.penetrating = e.penetrating;
      s.buckled = e.buckled;
      s.bent = e.bent;
      s.performance_index_mean = e.performance_index.mean;
      s.angle_max = e.angle.max;
      s.bending_force_max = e.bending_force.max;
      s.spring_energy_total = e.spring_energy.total;
    }
    const std::size_t finished = done += range.size();
    if (options.progress) options.progress(static_cast<double>(finished) / vertices.size());
  });
  return result;
}

}  // namespace needlekit::patch
