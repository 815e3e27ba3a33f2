// Internal: the element colouring of the threaded assembly. The elements are put in order along a Morton (Z-order)
// curve of their centroids and cut into blocks of consecutive elements; the blocks are coloured greedily so that no
// two blocks of a colour share a node. One thread assembles one whole block at a time: consecutive elements share
// nodes, so the displacements, forces and matrix entries they touch are still in cache (the element-by-element
// colouring it replaces sent every colour across the whole mesh), and each entry receives its terms in the same
// order whatever the number of threads.
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace needlekit::fem::detail {

struct ElementColouring {
  std::vector<int> elements;          // every element once: block after block, colour after colour
  std::vector<size_t> block_begin;    // per block, its first position in `elements`; one more entry: the end
  std::vector<size_t> colour_begin;   // per colour, its first block; one more entry: the number of blocks
  size_t colours() const { return colour_begin.size() - 1; }
  // The elements of block b, in the order a thread assembles them.
  std::span<const int> block(size_t b) const {
    return std::span<const int>(elements).subspan(block_begin[b], block_begin[b + 1] - block_begin[b]);
  }
};

// Elements per block: enough to reuse the nodes of a small patch, few enough that a colour has many blocks.
inline constexpr int kColouringBlock = 64;

// `connectivity`: nodes_per_element node indices per element; `nodes`: their positions.
ElementColouring element_colouring(const std::vector<int>& connectivity, int nodes_per_element,
                                   const std::vector<Eigen::Vector3d>& nodes, int block = kColouringBlock);

}  // namespace needlekit::fem::detail
