// The tangent's pattern (internal fem::detail::upper_pattern) with the free dofs numbered in any node order
// (dof_map; the solver numbers them along a Morton curve): every pair of free dofs whose nodes share an element is
// stored exactly once, as (row <= column), and the rows of each column are sorted.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "../../src/fem/boundary_conditions.hpp"
#include "../../src/fem/sparse_pattern.hpp"
#include "../support/bottom_fixed_block.hpp"

using namespace needlekit;

TEST(UpperPattern, HoldsEveryCouplingOnceInAnyNodeOrder) {
  test::BottomFixedBlock block = test::bottom_fixed_block(4, 4, 3);
  const mesh::TetMesh& m = block.mesh;
  const int nodes = static_cast<int>(m.nodes.size());
  std::vector<char>& fixed = block.fixed;
  fixed[3 * 5 + 1] = 1;  // a node with some of its dofs free

  std::vector<int> identity(static_cast<size_t>(nodes)), shuffled;
  std::iota(identity.begin(), identity.end(), 0);
  shuffled = identity;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(3));
  for (const std::vector<int>* order : {&identity, &shuffled}) {
    const fem::detail::DofMap dofs = fem::detail::dof_map(fixed, {}, *order);
    std::set<std::pair<int64_t, int64_t>> expected;
    for (const auto& t : m.tets)
      for (int a : t)
        for (int b : t)
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
              const int r = dofs.free_index[static_cast<size_t>(3 * a + i)];
              const int c = dofs.free_index[static_cast<size_t>(3 * b + j)];
              if (r >= 0 && c >= 0 && r <= c) expected.emplace(r, c);
            }
    const fem::detail::UpperPattern p = fem::detail::upper_pattern(block.connectivity, 4, nodes, dofs.free_index);
    ASSERT_EQ(p.column_pointers.size(), dofs.free_dofs.size() + 1);
    std::set<std::pair<int64_t, int64_t>> stored;
    for (size_t c = 0; c + 1 < p.column_pointers.size(); ++c)
      for (int64_t k = p.column_pointers[c]; k < p.column_pointers[c + 1]; ++k) {
        const int64_t r = p.row_indices[static_cast<size_t>(k)];
        EXPECT_LE(r, static_cast<int64_t>(c));
        if (k > p.column_pointers[c]) EXPECT_LT(p.row_indices[static_cast<size_t>(k) - 1], r) << "column " << c;
        stored.emplace(r, static_cast<int64_t>(c));
      }
    EXPECT_EQ(stored.size(), p.row_indices.size()) << "an entry stored twice";
    EXPECT_EQ(stored, expected);
  }
}
