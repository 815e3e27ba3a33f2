// Internal: points in the order of a Morton (Z-order) curve (Morton 1966): points close in the order are close in
// space. The assembly takes elements in this order of their centroids (element_colouring.hpp), and the free dofs
// are numbered in this order of their nodes (boundary_conditions.hpp), so that an element's matrix entries, the
// vector entries a product gathers and the rows it scatters to lie near those of the last ones, in cache.
#pragma once
#include <Eigen/Core>
#include <vector>

namespace needlekit::fem::detail {

// The indices of `points` sorted by the Morton code of their cell in a 2^21-per-axis grid over the box [low, high]
// (a point outside it is clamped to its faces). Stable: points of one cell keep their index order.
std::vector<int> morton_order(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& low,
                              const Eigen::Vector3d& high);

}  // namespace needlekit::fem::detail
