#include "element_colouring.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

#include "morton_order.hpp"

namespace needlekit::fem::detail {

ElementColouring element_colouring(const std::vector<int>& connectivity, int nodes_per_element,
                                   const std::vector<Eigen::Vector3d>& nodes, int block) {
  const size_t nn = static_cast<size_t>(nodes_per_element);
  const size_t ne = connectivity.size() / nn;
  // Morton order of the centroids (of the first four nodes: the corners), in the mesh's bounding box.
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::max()), high = -low;
  for (const Eigen::Vector3d& p : nodes) low = low.cwiseMin(p), high = high.cwiseMax(p);
  std::vector<Eigen::Vector3d> centroids(ne, Eigen::Vector3d::Zero());
  for (size_t e = 0; e < ne; ++e) {
    for (size_t a = 0; a < 4; ++a) centroids[e] += nodes[static_cast<size_t>(connectivity[e * nn + a])];
    centroids[e] /= 4;
  }
  const std::vector<int> order = morton_order(centroids, low, high);

  // Greedy block colouring: each block takes the first colour none of its nodes has yet (at most 256).
  const size_t blocks = (ne + static_cast<size_t>(block) - 1) / static_cast<size_t>(block);
  // The positions in `order` of block b's elements.
  const auto block_range = [&](size_t b) {
    const size_t first = b * static_cast<size_t>(block);
    return std::pair{first, std::min(ne, first + static_cast<size_t>(block))};
  };
  std::vector<std::array<uint64_t, 4>> used(nodes.size(), {0, 0, 0, 0});
  std::vector<int> colour(blocks);
  int colours = 0;
  for (size_t b = 0; b < blocks; ++b) {
    const auto [first, last] = block_range(b);
    std::array<uint64_t, 4> mask{0, 0, 0, 0};
    for (size_t k = first; k < last; ++k)
      for (size_t a = 0; a < nn; ++a)
        for (int w = 0; w < 4; ++w) mask[w] |= used[static_cast<size_t>(connectivity[order[k] * nn + a])][w];
    int c = -1;
    for (int w = 0; w < 4 && c < 0; ++w)
      if (~mask[w]) c = 64 * w + __builtin_ctzll(~mask[w]);
    // 256 colours are far more than blocks of a tetrahedral mesh need (a block meets a few dozen others); never
    // share a colour between blocks with a common node (threads would add into the same entries).
    if (c < 0) throw std::logic_error("element colouring: a block meets more than 255 others");
    colour[b] = c;
    colours = std::max(colours, c + 1);
    for (size_t k = first; k < last; ++k)
      for (size_t a = 0; a < nn; ++a)
        used[static_cast<size_t>(connectivity[order[k] * nn + a])][c / 64] |= uint64_t{1} << (c % 64);
  }

  ElementColouring result;
  result.elements.reserve(ne);
  result.block_begin.reserve(blocks + 1);
  result.colour_begin.assign(1, 0);
  for (int c = 0; c < colours; ++c) {
    for (size_t b = 0; b < blocks; ++b) {
      if (colour[b] != c) continue;
      result.block_begin.push_back(result.elements.size());
      const auto [first, last] = block_range(b);
      result.elements.insert(result.elements.end(), order.begin() + static_cast<std::ptrdiff_t>(first),
                             order.begin() + static_cast<std::ptrdiff_t>(last));
    }
    result.colour_begin.push_back(result.block_begin.size());
  }
  result.block_begin.push_back(result.elements.size());
  return result;
}

}  // namespace needlekit::fem::detail
