#include "needlekit/mesh/coarse_level.hpp"

#include <tbb/parallel_for.h>

#include <utility>

#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/tet_locator.hpp"

namespace needlekit::mesh {

CoarseLevel interpolating_coarse_level(const TetMesh& fine, const TetMesh& coarse) {
  if (coarse.tets.empty()) throw InvalidInput("coarse level: the coarse mesh has no tetrahedra");
  CoarseLevel level;
  level.nodes = static_cast<int>(coarse.nodes.size());
  level.tets = coarse.tets;
  const TetLocator locator(coarse.nodes, coarse.tets);
  level.interpolation.resize(fine.nodes.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, fine.nodes.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t n = r.begin(); n < r.end(); ++n) {
      const TetLocation location = locator.locate(fine.nodes[n]);  // the tetrahedron the node is most inside of
      const int best = location.tet;
      Eigen::Vector4d best_weights = location.barycentric;
      // Clipped at zero, and a node on a face or an edge (weights of rounding size) keeps only that face's or edge's
      // nodes, so that A_c couples no more coarse nodes than needed.
      best_weights = (best_weights.array() < 1e-10).select(0.0, best_weights);
      best_weights /= best_weights.sum();
      NodeInterpolation& out = level.interpolation[n];
      int slot = 0;
      for (size_t k = 0; k < 4; ++k)
        if (best_weights[static_cast<Eigen::Index>(k)] > 0) {
          out.nodes[static_cast<size_t>(slot)] = coarse.tets[static_cast<size_t>(best)][k];
          out.weights[static_cast<size_t>(slot)] = best_weights[static_cast<Eigen::Index>(k)];
          ++slot;
        }
    }
  });
  return level;
}

}  // namespace needlekit::mesh
