#include "sparse_pattern.hpp"

namespace needlekit::fem::detail {

UpperPattern upper_pattern(const std::vector<int>& connectivity, int nodes_per_element, int node_count,
                           const std::vector<int>& free_index, const std::vector<int>* group_pointers,
                           const std::vector<int>* group_nodes) {
  const size_t ne = connectivity.size() / static_cast<size_t>(nodes_per_element);
  std::vector<std::vector<int>> adjacent(static_cast<size_t>(node_count));  // per column node, row nodes <= it
  const auto couple = [&](const int* c, int n) {
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        if (c[b] <= c[a]) adjacent[static_cast<size_t>(c[a])].push_back(c[b]);
  };
  for (size_t e = 0; e < ne; ++e) couple(&connectivity[e * static_cast<size_t>(nodes_per_element)], nodes_per_element);
  if (group_pointers)
    for (size_t g = 0; g + 1 < group_pointers->size(); ++g) {
      const int begin = (*group_pointers)[g], end = (*group_pointers)[g + 1];
      if (end > begin) couple(group_nodes->data() + begin, end - begin);
    }
  int64_t free_count = 0;
  for (int index : free_index) free_count += index >= 0;
  UpperPattern p;
  p.column_pointers.assign(static_cast<size_t>(free_count) + 1, 0);
  for (int n = 0; n < node_count; ++n) {
    auto& rows = adjacent[static_cast<size_t>(n)];
    std::sort(rows.begin(), rows.end());
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
