// The non-nested coarse level (mesh::interpolating_coarse_level): each fine node is a convex combination of the
// nodes of one coarse tetrahedron that reproduces its position (so every linear field is interpolated exactly), and
// on a mesh that was split from the coarse one it finds the nested parentage again.
#include <gtest/gtest.h>

#include <algorithm>

#include "needlekit/core/errors.hpp"
#include "needlekit/mesh/coarse_level.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"
#include "needlekit/mesh/uniform_refinement.hpp"

using namespace needlekit;
using namespace needlekit::mesh;

namespace {

TetMesh graded_block(int cells, int tets_per_hex) {
  StructuredBlockOptions o;
  o.width = 2e-3, o.length = 1.5e-3, o.height = 1e-3;
  o.nx = o.ny = o.nz = cells;
  o.tets_per_hex = tets_per_hex;
  o.grading = 3;
  return structured_block_mesh(o);
}

Eigen::Vector3d interpolated_position(const CoarseLevel& level, const TetMesh& coarse, size_t fine_node) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  const NodeInterpolation& p = level.interpolation[fine_node];
  for (size_t k = 0; k < 4; ++k)
    if (p.nodes[k] >= 0) x += p.weights[k] * coarse.nodes[static_cast<size_t>(p.nodes[k])];
  return x;
}

}  // namespace

TEST(CoarseLevel, InterpolatesEveryFineNodeOfAnIndependentMeshExactly) {
  // 7 graded cells and 6 tets per hex against 4 cells and 5 tets per hex: no fine node lies on a coarse node by
  // construction except the block's corners.
  const TetMesh fine = graded_block(7, 6), coarse = graded_block(4, 5);
  const CoarseLevel level = interpolating_coarse_level(fine, coarse);
  EXPECT_EQ(level.nodes, static_cast<int>(coarse.nodes.size()));
  EXPECT_EQ(level.tets, coarse.tets);
  ASSERT_EQ(level.interpolation.size(), fine.nodes.size());
  for (size_t n = 0; n < fine.nodes.size(); ++n) {
    const NodeInterpolation& p = level.interpolation[n];
    double sum = 0;
    for (size_t k = 0; k < 4; ++k) {
      EXPECT_GE(p.weights[k], 0.0);
      EXPECT_EQ(p.nodes[k] < 0, p.weights[k] == 0) << "node " << n << " slot " << k;
      sum += p.weights[k];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_LT((interpolated_position(level, coarse, n) - fine.nodes[n]).norm(), 1e-12 * 2e-3) << "node " << n;
  }
}

TEST(CoarseLevel, FindsTheNestedParentsOfASplitMesh) {
  const TetMesh coarse = graded_block(3, 6);
  const UniformRefinement split = refine_uniformly(coarse);
  const CoarseLevel level = interpolating_coarse_level(split.mesh, coarse);
  for (size_t n = 0; n < split.mesh.nodes.size(); ++n) {
    const NodeInterpolation& found = level.interpolation[n];
    const NodeInterpolation& nested = split.coarse.interpolation[n];
    for (size_t k = 0; k < 4; ++k) {  // the same nodes with the same weights, in any order
      if (nested.nodes[k] < 0) continue;
      const auto slot = std::find(found.nodes.begin(), found.nodes.end(), nested.nodes[k]) - found.nodes.begin();
      ASSERT_LT(slot, 4) << "fine node " << n << " lost coarse node " << nested.nodes[k];
      EXPECT_NEAR(found.weights[static_cast<size_t>(slot)], nested.weights[k], 1e-9);
    }
    EXPECT_EQ(std::count(found.nodes.begin(), found.nodes.end(), -1),
              std::count(nested.nodes.begin(), nested.nodes.end(), -1))
        << "fine node " << n;
  }
}

TEST(CoarseLevel, RefusesAnEmptyCoarseMesh) {
  EXPECT_THROW(interpolating_coarse_level(graded_block(2, 6), TetMesh{}), InvalidInput);
}
