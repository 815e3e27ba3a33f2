// Uniform (red) refinement: eight right-handed children per tetrahedron filling it exactly, one new node per edge at
// its midpoint, parentage as the two-grid solver reads it, and bounded shape degradation over repeated splitting.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "needlekit/mesh/mesh_validation.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"
#include "needlekit/mesh/uniform_refinement.hpp"

using namespace needlekit;
using namespace needlekit::mesh;

namespace {

double volume(const TetMesh& m, size_t e) {
  const auto& t = m.tets[e];
  return signed_volume(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
}

double min_quality(const TetMesh& m) { return tet_mesh_check(m).min_quality; }

TetMesh two_layer_block() {
  StructuredBlockOptions o;
  o.width = 2e-3, o.length = 1e-3, o.height = 0.5e-3;
  o.nx = 4, o.ny = 3, o.nz = 2;
  o.tets_per_hex = 5;
  TetMesh m = structured_block_mesh(o);
  m.layers.push_back({"lower", 0.25e-3, 2e5, 0.45});
  for (size_t e = 0; e < m.tets.size(); ++e) {
    double z = 0;
    for (int a : m.tets[e]) z += m.nodes[static_cast<size_t>(a)].z() / 4;
    m.tet_layer[e] = z < -0.25e-3 ? 1 : 0;
  }
  return m;
}

}  // namespace

TEST(UniformRefinement, EightRightHandedChildrenFillEachParent) {
  const TetMesh coarse = two_layer_block();
  const UniformRefinement r = refine_uniformly(coarse);
  ASSERT_EQ(r.mesh.tets.size(), 8 * coarse.tets.size());
  ASSERT_EQ(r.mesh.tet_layer.size(), r.mesh.tets.size());
  for (size_t e = 0; e < coarse.tets.size(); ++e) {
    double children = 0;
    for (size_t k = 0; k < 8; ++k) {
      const size_t child = 8 * e + k;
      EXPECT_GT(volume(r.mesh, child), 0) << "child " << child;
      EXPECT_EQ(r.mesh.tet_layer[child], coarse.tet_layer[e]);
      children += volume(r.mesh, child);
    }
    EXPECT_NEAR(children / volume(coarse, e), 1.0, 1e-12) << "parent " << e;
  }
  EXPECT_TRUE(tet_mesh_check(r.mesh).valid());
}

TEST(UniformRefinement, OneMidpointPerEdgeAndCoarseNodesKeepTheirIndex) {
  const TetMesh coarse = two_layer_block();
  const UniformRefinement r = refine_uniformly(coarse);
  std::set<std::pair<int, int>> edges;
  for (const auto& t : coarse.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edges.insert({std::min(t[i], t[j]), std::max(t[i], t[j])});
  const int nc = static_cast<int>(coarse.nodes.size());
  ASSERT_EQ(r.coarse.nodes, nc);
  ASSERT_EQ(r.coarse.tets, coarse.tets);
  ASSERT_EQ(r.mesh.nodes.size(), coarse.nodes.size() + edges.size());
  ASSERT_EQ(r.coarse.interpolation.size(), r.mesh.nodes.size());
  std::set<std::pair<int, int>> parents_seen;
  for (size_t n = 0; n < r.mesh.nodes.size(); ++n) {
    const NodeInterpolation& p = r.coarse.interpolation[n];
    if (static_cast<int>(n) < nc) {
      EXPECT_EQ(p.nodes, (std::array<int, 4>{static_cast<int>(n), -1, -1, -1}));
      EXPECT_EQ(p.weights, (std::array<double, 4>{1, 0, 0, 0}));
      EXPECT_EQ(r.mesh.nodes[n], coarse.nodes[n]);
      continue;
    }
    const int a = p.nodes[0], b = p.nodes[1];
    EXPECT_EQ(p.weights, (std::array<double, 4>{0.5, 0.5, 0, 0}));
    EXPECT_TRUE(edges.count({std::min(a, b), std::max(a, b)})) << "node " << n << " is not on a coarse edge";
    EXPECT_TRUE(parents_seen.insert({std::min(a, b), std::max(a, b)}).second) << "edge split twice";
    EXPECT_LT((r.mesh.nodes[n] - 0.5 * (coarse.nodes[a] + coarse.nodes[b])).norm(), 1e-15);
  }
}

TEST(UniformRefinement, ShapeStaysBoundedOverRepeatedSplitting) {
  // Splitting along the octahedron's shortest diagonal keeps the children within a few similarity classes: the
  // worst quality settles instead of falling with every level (a fixed diagonal choice can decay geometrically).
  TetMesh m;
  m.nodes = {{0, 0, 0}, {1e-4, 0, 0}, {0.3e-4, 0.9e-4, 0}, {0.4e-4, 0.3e-4, 0.8e-4}};
  m.tets = {{0, 1, 2, 3}};
  m.tet_layer = {0};
  m.layers = {{"gel", 1e-4, 2e5, 0.45}};
  const double q0 = min_quality(m);
  double q = q0;
  for (int level = 1; level <= 3; ++level) {
    m = refine_uniformly(m).mesh;
    q = min_quality(m);
  }
  EXPECT_GT(q, 0.5 * q0) << "worst child quality after three splits";
  EXPECT_EQ(m.tets.size(), 512u);
}
