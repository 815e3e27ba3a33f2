#include "sparse_pattern.hpp"

#include <algorithm>

namespace needlekit::fem::detail {

UpperPattern upper_pattern(const std::vector<int>& connectivity, int nodes_per_element, int node_count,
                           const std::vector<int>& free_index, const std::vector<int>* group_pointers,
                           const std::vector<int>* group_nodes) {
  // A node's rank: its first free index (-1: none free). The free dofs are numbered node by node, so the ranks order
  // the nodes as their columns are ordered.
  std::vector<int> rank(static_cast<size_t>(node_count), -1);
  for (int n = 0; n < node_count; ++n)
    for (int i = 2; i >= 0; --i)
      if (const int f = free_index[static_cast<size_t>(3 * n + i)]; f >= 0) rank[static_cast<size_t>(n)] = f;
  const size_t ne = connectivity.size() / static_cast<size_t>(nodes_per_element);
  std::vector<std::vector<int>> adjacent(static_cast<size_t>(node_count));  // per column node, row nodes up to it
  const auto couple = [&](const int* c, int n) {
    for (int a = 0; a < n; ++a) {
      const int column_rank = rank[static_cast<size_t>(c[a])];
      if (column_rank < 0) continue;
      for (int b = 0; b < n; ++b)
        if (const int row_rank = rank[static_cast<size_t>(c[b])]; row_rank >= 0 && row_rank <= column_rank)
          adjacent[static_cast<size_t>(c[a])].push_back(c[b]);
    }
  };
  for (size_t e = 0; e < ne; ++e) couple(&connectivity[e * static_cast<size_t>(nodes_per_element)], nodes_per_element);
  if (group_pointers)
    for (size_t g = 0; g + 1 < group_pointers->size(); ++g) {
      const int begin = (*group_pointers)[g], end = (*group_pointers)[g + 1];
      if (end > begin) couple(group_nodes->data() + begin, end - begin);
    }
  std::vector<int> columns_nodes;  // the nodes with a free dof, in column order
  for (int n = 0; n < node_count; ++n)
    if (rank[static_cast<size_t>(n)] >= 0) columns_nodes.push_back(n);
  std::sort(columns_nodes.begin(), columns_nodes.end(),
            [&](int a, int b) { return rank[static_cast<size_t>(a)] < rank[static_cast<size_t>(b)]; });
  int64_t free_count = 0;
  for (int index : free_index) free_count += index >= 0;
  UpperPattern p;
  p.column_pointers.assign(static_cast<size_t>(free_count) + 1, 0);
  for (int n : columns_nodes) {
    auto& rows = adjacent[static_cast<size_t>(n)];
    std::sort(rows.begin(), rows.end(),
              [&](int a, int b) { return rank[static_cast<size_t>(a)] < rank[static_cast<size_t>(b)]; });
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    for (int i = 0; i < 3; ++i) {
      const int column = free_index[static_cast<size_t>(3 * n + i)];
      if (column < 0) continue;
      for (int nb : rows)
        for (int j = 0; j < 3; ++j) {
          const int row = free_index[static_cast<size_t>(3 * nb + j)];
          if (row >= 0 && row <= column) p.row_indices.push_back(row);
        }
      p.column_pointers[static_cast<size_t>(column) + 1] = static_cast<int64_t>(p.row_indices.size());
    }
    std::vector<int>().swap(rows);
  }
  return p;
}

}  // namespace needlekit::fem::detail
