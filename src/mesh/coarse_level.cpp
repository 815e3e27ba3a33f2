#include "needlekit/mesh/coarse_level.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/LU>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <limits>
#include <utility>

#include "needlekit/core/errors.hpp"

namespace needlekit::mesh {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using Point = bg::model::point<double, 3, bg::cs::cartesian>;
using Box = bg::model::box<Point>;
using BoxEntry = std::pair<Box, int>;  // a coarse tetrahedron's bounding box and index

Point point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// Barycentric coordinates of p in tetrahedron t of `coarse`.
Eigen::Vector4d barycentric(const TetMesh& coarse, const std::array<int, 4>& t, const Eigen::Vector3d& p) {
  const Eigen::Vector3d& x0 = coarse.nodes[static_cast<size_t>(t[0])];
  Eigen::Matrix3d edges;
  for (int k = 0; k < 3; ++k) edges.col(k) = coarse.nodes[static_cast<size_t>(t[static_cast<size_t>(k) + 1])] - x0;
  const Eigen::Vector3d l = edges.partialPivLu().solve(p - x0);
  return {1 - l.sum(), l.x(), l.y(), l.z()};
}

}  // namespace

CoarseLevel interpolating_coarse_level(const TetMesh& fine, const TetMesh& coarse) {
  if (coarse.tets.empty()) throw InvalidInput("coarse level: the coarse mesh has no tetrahedra");
  CoarseLevel level;
  level.nodes = static_cast<int>(coarse.nodes.size());
  level.tets = coarse.tets;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  std::vector<BoxEntry> boxes;
  boxes.reserve(coarse.tets.size());
  for (size_t e = 0; e < coarse.tets.size(); ++e) {
    Eigen::Vector3d lo = coarse.nodes[static_cast<size_t>(coarse.tets[e][0])], hi = lo;
    for (int a : coarse.tets[e]) {
      lo = lo.cwiseMin(coarse.nodes[static_cast<size_t>(a)]);
      hi = hi.cwiseMax(coarse.nodes[static_cast<size_t>(a)]);
    }
    low = low.cwiseMin(lo);
    high = high.cwiseMax(hi);
    boxes.emplace_back(Box(point(lo), point(hi)), static_cast<int>(e));
  }
  const bgi::rtree<BoxEntry, bgi::rstar<16>> tree(boxes.begin(), boxes.end());  // bulk-loaded (packing)
  const double slack = 1e-9 * (high - low).norm();  // a node on a face or an edge is inside both neighbours' boxes

  level.interpolation.resize(fine.nodes.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, fine.nodes.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<BoxEntry> candidates;
    for (size_t n = r.begin(); n < r.end(); ++n) {
      const Eigen::Vector3d& p = fine.nodes[n];
      candidates.clear();
      const Eigen::Vector3d s = Eigen::Vector3d::Constant(slack);
      tree.query(bgi::intersects(Box(point(p - s), point(p + s))), std::back_inserter(candidates));
      if (candidates.empty()) tree.query(bgi::nearest(point(p), 8), std::back_inserter(candidates));
      int best = -1;
      Eigen::Vector4d best_weights = Eigen::Vector4d::Zero();
      for (const BoxEntry& candidate : candidates) {  // the tetrahedron the node is most inside of
        const Eigen::Vector4d w = barycentric(coarse, coarse.tets[static_cast<size_t>(candidate.second)], p);
        if (best < 0 || w.minCoeff() > best_weights.minCoeff() ||
            (w.minCoeff() == best_weights.minCoeff() && candidate.second < best)) {
          best = candidate.second;
          best_weights = w;
        }
      }
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
