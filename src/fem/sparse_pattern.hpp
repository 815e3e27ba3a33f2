// Internal: the compressed-column pattern of a symmetric FE stiffness matrix (upper triangle, row <= column) over
// the free degrees of freedom, three per node, from the element connectivity.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace needlekit::fem::detail {

struct UpperPattern {
  std::vector<int64_t> column_pointers;  // free dofs + 1
  std::vector<int64_t> row_indices;      // sorted within each column
};

// `connectivity`: nodes_per_element node indices per element; `free_index`: per dof (3 * node + component) its
// index among the free dofs, or -1, numbered node by node (a node's free dofs consecutive, by component; the nodes in
// any order, dof_map). Two free dofs couple when their nodes share an element.
// `group_pointers`/`group_nodes` (optional, CSR): further groups of nodes that couple all their free dofs (the node
// patches of the nodal-averaged tetrahedron).
UpperPattern upper_pattern(const std::vector<int>& connectivity, int nodes_per_element, int node_count,
                           const std::vector<int>& free_index, const std::vector<int>* group_pointers = nullptr,
                           const std::vector<int>* group_nodes = nullptr);

// Position in the pattern's arrays of the entry (row, column), row <= column; the entry must exist.
inline int64_t entry_position(const UpperPattern& p, int64_t row, int64_t column) {
  const auto first = p.row_indices.begin() + p.column_pointers[static_cast<size_t>(column)];
  const auto last = p.row_indices.begin() + p.column_pointers[static_cast<size_t>(column) + 1];
  return std::lower_bound(first, last, row) - p.row_indices.begin();
}

}  // namespace needlekit::fem::detail
