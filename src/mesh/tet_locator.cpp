#include "needlekit/mesh/tet_locator.hpp"

#include <Eigen/LU>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <iterator>
#include <limits>
#include <utility>

#include "needlekit/core/errors.hpp"

namespace needlekit::mesh {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using Point = bg::model::point<double, 3, bg::cs::cartesian>;
using Box = bg::model::box<Point>;
using BoxEntry = std::pair<Box, int>;  // a tetrahedron's bounding box and index

Point point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

struct TetLocator::Tree {
  bgi::rtree<BoxEntry, bgi::rstar<16>> rtree;
};

TetLocator::TetLocator(const std::vector<Eigen::Vector3d>& nodes, const std::vector<std::array<int, 4>>& tets)
    : nodes_(nodes), tets_(tets) {
  if (tets_.empty()) throw InvalidInput("point location: the mesh has no tetrahedra");
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  std::vector<BoxEntry> boxes;
  boxes.reserve(tets_.size());
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    Eigen::Vector3d lo = nodes_[static_cast<std::size_t>(tets_[e][0])], hi = lo;
    for (int a : tets_[e]) {
      lo = lo.cwiseMin(nodes_[static_cast<std::size_t>(a)]);
      hi = hi.cwiseMax(nodes_[static_cast<std::size_t>(a)]);
    }
    low = low.cwiseMin(lo);
    high = high.cwiseMax(hi);
    boxes.emplace_back(Box(point(lo), point(hi)), static_cast<int>(e));
  }
  tree_ = std::make_unique<Tree>(Tree{{boxes.begin(), boxes.end()}});  // bulk-loaded (packing)
  slack_ = 1e-9 * (high - low).norm();
}

TetLocator::~TetLocator() = default;
TetLocator::TetLocator(TetLocator&&) noexcept = default;
TetLocator& TetLocator::operator=(TetLocator&&) noexcept = default;

TetLocation TetLocator::locate(const Eigen::Vector3d& p) const {
  std::vector<BoxEntry> candidates;
  const Eigen::Vector3d s = Eigen::Vector3d::Constant(slack_);
  tree_->rtree.query(bgi::intersects(Box(point(p - s), point(p + s))), std::back_inserter(candidates));
  if (candidates.empty()) tree_->rtree.query(bgi::nearest(point(p), 8), std::back_inserter(candidates));
  TetLocation best;
  for (const BoxEntry& candidate : candidates) {
    const std::array<int, 4>& t = tets_[static_cast<std::size_t>(candidate.second)];
    const Eigen::Vector3d& x0 = nodes_[static_cast<std::size_t>(t[0])];
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k) edges.col(k) = nodes_[static_cast<std::size_t>(t[static_cast<std::size_t>(k) + 1])] - x0;
    const Eigen::Vector3d l = edges.partialPivLu().solve(p - x0);
    const Eigen::Vector4d w(1 - l.sum(), l.x(), l.y(), l.z());
    if (!w.allFinite()) continue;  // a degenerate tetrahedron holds no point
    if (best.tet < 0 || w.minCoeff() > best.barycentric.minCoeff() ||
        (w.minCoeff() == best.barycentric.minCoeff() && candidate.second < best.tet)) {
      best.tet = candidate.second;
      best.barycentric = w;
    }
  }
  return best;
}

}  // namespace needlekit::mesh
