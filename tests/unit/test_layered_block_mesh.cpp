// The Gmsh layered block: layer volumes are exact (conforming planar interfaces), elements are right-handed and well
// shaped in the thin stratum corneum, the mesh is refined at the insertion sites, and bad options are rejected by
// name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "needlekit/core/errors.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/mesh_validation.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

// A small skin block (600 x 500 um, default §3.3.2 layers but 400 um tall) that meshes in well under a second.
mesh::LayeredBlockOptions small_skin_block() {
  mesh::LayeredBlockOptions o;
  o.width = 600e-6;
  o.length = 500e-6;
  o.layers = materials::skin_layers();
  o.layers[2].thickness = 240e-6;
  o.size_at_site = 30e-6;
  o.refinement_radius = 80e-6;
  o.size_far = 120e-6;
  o.threads = 1;
  return o;
}

}  // namespace

TEST(LayeredBlockMesh, LayerVolumesAreWidthTimesLengthTimesThickness) {
  const mesh::LayeredBlockOptions o = small_skin_block();
  const mesh::LayeredBlockResult r = mesh::layered_block_mesh(o);
  ASSERT_EQ(r.mesh.layers.size(), 3u);
  ASSERT_EQ(r.quality.size(), 3u);
  std::vector<double> volume(3, 0.0);
  const auto& m = r.mesh;
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const auto& t = m.tets[e];
    const double v = mesh::signed_volume(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
    EXPECT_GT(v, 0) << "tet " << e << " is not right-handed";
    volume[m.tet_layer[e]] += v;
  }
  double total = 0;
  for (int i = 0; i < 3; ++i) {
    const double expected = o.width * o.length * o.layers[i].thickness;
    EXPECT_NEAR(volume[i], expected, 1e-9 * expected) << o.layers[i].name;
    EXPECT_EQ(r.quality[i].name, o.layers[i].name);
    EXPECT_GT(r.quality[i].tets, 0);
    total += volume[i];
  }
  EXPECT_NEAR(total, o.width * o.length * 400e-6, 1e-9 * total);
  // Every node lies in the block; each layer's elements lie between its interfaces.
  const double top[] = {0, -20e-6, -160e-6}, bottom[] = {-20e-6, -160e-6, -400e-6};
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    for (int k : m.tets[e]) {
      const double z = m.nodes[k].z();
      ASSERT_LE(z, top[m.tet_layer[e]] + 1e-12);
      ASSERT_GE(z, bottom[m.tet_layer[e]] - 1e-12);
    }
  }
  // The insertion site is a mesh node.
  bool site = false;
  for (const auto& p : m.nodes) site = site || p.norm() < 1e-12;
  EXPECT_TRUE(site);
}

TEST(LayeredBlockMesh, ThinStratumCorneumIsWellShaped) {
  const mesh::LayeredBlockResult r = mesh::layered_block_mesh(small_skin_block());
  for (const mesh::LayerQuality& q : r.quality) {
    EXPECT_GT(q.min_quality, 0.1) << q.name;
    EXPECT_GT(q.mean_quality, 0.6) << q.name;
  }
  EXPECT_TRUE(mesh::tet_mesh_check(r.mesh).valid());
}

TEST(LayeredBlockMesh, RefinesAtEachInsertionSite) {
  mesh::LayeredBlockOptions o = small_skin_block();
  o.layers = {{"phantom", 300e-6, 0.2e6, 0.49}};
  o.insertion_sites = {{-150e-6, 0}, {150e-6, 0}};
  o.size_at_site = 20e-6;
  o.refinement_radius = 40e-6;
  o.size_far = 150e-6;
  const mesh::LayeredBlockResult r = mesh::layered_block_mesh(o);
  // Mean edge length of the elements touching each site vs the elements far from both (x ~ 0 is between them and
  // 150 um away, the corners are farther).
  auto mean_edge = [&](auto&& select) {
    double sum = 0;
    int n = 0;
    for (const auto& t : r.mesh.tets) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int k : t) c += r.mesh.nodes[k] / 4;
      if (!select(c)) continue;
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) sum += (r.mesh.nodes[t[a]] - r.mesh.nodes[t[b]]).norm(), ++n;
    }
    return n ? sum / n : 0.0;
  };
  for (double x : {-150e-6, 150e-6}) {
    const double near = mean_edge([&](const Eigen::Vector3d& c) { return (c - Eigen::Vector3d(x, 0, 0)).norm() < 30e-6; });
    EXPECT_GT(near, 0);
    EXPECT_LT(near, 1.5 * o.size_at_site) << "site x = " << x;
  }
  const double far = mean_edge([](const Eigen::Vector3d& c) { return c.z() < -200e-6 && std::abs(c.y()) > 150e-6; });
  EXPECT_GT(far, 3 * o.size_at_site);
}

TEST(LayeredBlockMesh, RejectsBadOptionsByName) {
  mesh::LayeredBlockOptions o = small_skin_block();
  o.layers[1].thickness = 0;
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("layers[1] (\"epidermis\").thickness: 0 um")));
  o = small_skin_block();
  o.layers[0].thickness = -5e-6;
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("thickness: -5 um; expected a positive thickness")));
  o = small_skin_block();
  o.size_far = 10e-6;
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); }, testing::ThrowsMessage<InvalidInput>(HasSubstr("size_far")));
  o = small_skin_block();
  o.insertion_sites = {{400e-6, 0}};
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("insertion site 0 at (400, 0) um")));
  o = small_skin_block();
  o.layers[2].poisson_ratio = 0.5;
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); }, testing::ThrowsMessage<InvalidInput>(HasSubstr("poisson_ratio")));
}

TEST(LayeredBlockMesh, DefaultsAreTheDissertationSkin) {
  const mesh::LayeredBlockOptions o;
  EXPECT_DOUBLE_EQ(o.width, 3000e-6);
  EXPECT_DOUBLE_EQ(o.length, 3000e-6);
  const auto skin = materials::skin_layers();
  ASSERT_EQ(skin.size(), 3u);
  EXPECT_DOUBLE_EQ(skin[0].thickness, 20e-6);
  EXPECT_DOUBLE_EQ(skin[0].thickness + skin[1].thickness, 160e-6);
  EXPECT_NEAR(skin[0].thickness + skin[1].thickness + skin[2].thickness, 1150e-6, 1e-18);
  EXPECT_DOUBLE_EQ(skin[0].youngs_modulus, 100e6);
  EXPECT_DOUBLE_EQ(skin[1].youngs_modulus, 0.134e6);
  EXPECT_DOUBLE_EQ(skin[2].youngs_modulus, 0.08e6);
  for (const auto& l : skin) EXPECT_DOUBLE_EQ(l.poisson_ratio, 0.4);
}

TEST(LayeredBlockMesh, ConcurrentCallsAreSerialisedAndComplete) {
  // Gmsh is one global state: two threads meshing at once must both get a complete, valid mesh of the block, and
  // (the mesher being reproducible whatever the heap layout) the same one, bit for bit.
  const mesh::LayeredBlockOptions o = small_skin_block();
  mesh::LayeredBlockResult a, b;
  std::thread first([&] { a = mesh::layered_block_mesh(o); });
  std::thread second([&] { b = mesh::layered_block_mesh(o); });
  first.join();
  second.join();
  for (const mesh::LayeredBlockResult* r : {&a, &b}) {
    const mesh::TetMeshCheck check = mesh::tet_mesh_check(r->mesh);
    EXPECT_TRUE(check.valid());
    EXPECT_NEAR(check.volume, o.width * o.length * 400e-6, 1e-9 * check.volume);
    EXPECT_EQ(r->quality.size(), 3u);
  }
  ASSERT_EQ(a.mesh.nodes.size(), b.mesh.nodes.size());
  EXPECT_TRUE(a.mesh.nodes == b.mesh.nodes);
  EXPECT_TRUE(a.mesh.tets == b.mesh.tets);
}

TEST(LayeredBlockMesh, SiteCircleGivesNodesOnAFlatPunchEdge) {
  mesh::LayeredBlockOptions o = small_skin_block();
  o.site_circle_radius = 115e-6;  // the Sneddon case's 230 um flat cylinder
  o.refinement_radius = 150e-6;
  const mesh::LayeredBlockResult r = mesh::layered_block_mesh(o);
  // Nodes on the circle: at least 2 pi R / (1.5 size) of them, evenly around (every 30 degree sector has some).
  std::vector<int> sectors(12, 0);
  int on_circle = 0;
  for (const auto& p : r.mesh.nodes) {
    if (std::abs(p.z()) > 1e-12 || std::abs(std::hypot(p.x(), p.y()) - 115e-6) > 1e-3 * 115e-6) continue;
    ++on_circle;
    ++sectors[static_cast<int>((std::atan2(p.y(), p.x()) + M_PI) / (M_PI / 6)) % 12];
  }
  EXPECT_GE(on_circle, static_cast<int>(2 * M_PI * 115e-6 / (1.5 * o.size_at_site)));
  for (int n : sectors) EXPECT_GT(n, 0);
  EXPECT_TRUE(mesh::tet_mesh_check(r.mesh).valid());
  o.insertion_sites = {{-100e-6, 0}, {100e-6, 0}};
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("the 115 um circles of sites 0 and 1 overlap")));
  o.insertion_sites = {{200e-6, 0}};
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("leaves the top surface")));
}

TEST(LayeredBlockMesh, SplitMeshesAtTwiceTheSizeAndKeepsTheCoarseLevel) {
  // split: Gmsh at twice the sizes, then every tet split into eight. About as many elements as meshing at the
  // sizes directly, exact layer volumes, well-shaped layers, and the coarse level for the two-grid solver.
  mesh::LayeredBlockOptions o = small_skin_block();
  const mesh::LayeredBlockResult direct = mesh::layered_block_mesh(o);
  o.split = true;
  const mesh::LayeredBlockResult split = mesh::layered_block_mesh(o);
  EXPECT_FALSE(direct.coarse.has_value());
  ASSERT_TRUE(split.coarse.has_value());
  EXPECT_EQ(split.mesh.tets.size(), 8 * split.coarse->tets.size());
  EXPECT_EQ(split.coarse->interpolation.size(), split.mesh.nodes.size());
  const double ratio = static_cast<double>(split.mesh.tets.size()) / static_cast<double>(direct.mesh.tets.size());
  EXPECT_GT(ratio, 0.4);
  EXPECT_LT(ratio, 2.5);
  std::vector<double> volume(3, 0.0);
  for (std::size_t e = 0; e < split.mesh.tets.size(); ++e) {
    const auto& t = split.mesh.tets[e];
    const auto& p = split.mesh.nodes;
    volume[split.mesh.tet_layer[e]] += mesh::signed_volume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
  }
  for (int i = 0; i < 3; ++i) {
    const double expected = o.width * o.length * o.layers[i].thickness;
    EXPECT_NEAR(volume[i], expected, 1e-9 * expected) << o.layers[i].name;
    EXPECT_GT(split.quality[i].min_quality, 0.1) << split.quality[i].name;
  }
  EXPECT_TRUE(mesh::tet_mesh_check(split.mesh).valid());
}

TEST(LayeredBlockMesh, CoarseLevelMeshesTheBlockAgainAtThreeTimesTheSizes) {
  // coarse_level without split: the same mesh as without it, plus the block meshed at three times the sizes (the
  // default coarse_size_factor: a 27th of the elements in a uniform mesh) in which every node of the mesh is
  // interpolated.
  mesh::LayeredBlockOptions o = small_skin_block();
  const mesh::LayeredBlockResult direct = mesh::layered_block_mesh(o);
  o.coarse_level = true;
  const mesh::LayeredBlockResult with_coarse = mesh::layered_block_mesh(o);
  EXPECT_EQ(with_coarse.mesh.nodes, direct.mesh.nodes);
  EXPECT_EQ(with_coarse.mesh.tets, direct.mesh.tets);
  ASSERT_TRUE(with_coarse.coarse.has_value());
  const mesh::CoarseLevel& coarse = *with_coarse.coarse;
  ASSERT_EQ(coarse.interpolation.size(), direct.mesh.nodes.size());
  const double ratio = static_cast<double>(coarse.tets.size()) / static_cast<double>(direct.mesh.tets.size());
  EXPECT_GT(ratio, 1.0 / 40);
  EXPECT_LT(ratio, 1.0 / 6);  // 0.107: on this small block the graded region around the site is a large part
  for (const mesh::NodeInterpolation& p : coarse.interpolation) {
    EXPECT_NEAR(p.weights[0] + p.weights[1] + p.weights[2] + p.weights[3], 1.0, 1e-12);
    for (int a : p.nodes) EXPECT_LT(a, coarse.nodes);
  }
}

TEST(LayeredBlockMesh, CoarseSizeFactorSetsTheCoarseLevelsSizes) {
  // Three times the sizes (the default) instead of two: about (2/3)^3 of the coarse elements; a factor <= 1 is bad
  // input.
  mesh::LayeredBlockOptions o = small_skin_block();
  o.coarse_level = true;
  const mesh::LayeredBlockResult thrice = mesh::layered_block_mesh(o);
  o.coarse_size_factor = 2;
  const mesh::LayeredBlockResult twice = mesh::layered_block_mesh(o);
  EXPECT_EQ(thrice.mesh.tets, twice.mesh.tets);
  ASSERT_TRUE(twice.coarse && thrice.coarse);
  const double ratio =
      static_cast<double>(thrice.coarse->tets.size()) / static_cast<double>(twice.coarse->tets.size());
  EXPECT_GT(ratio, 0.5 * 8.0 / 27.0);
  EXPECT_LT(ratio, 2.0 * 8.0 / 27.0);
  o.coarse_size_factor = 1;
  EXPECT_THAT([&] { mesh::layered_block_mesh(o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("coarse_size_factor = 1; expected a value > 1")));
}

TEST(LayeredBlockMesh, NoFlatSliversInAThinLayerWithAlignedFaces) {
  // The default block with a 40 um tip size: the 20 um stratum corneum is one element thick. When its top and bottom
  // faces carried the same triangulation, half of the (then HXT, not reproducible) runs had a zero-volume tet
  // spanning a vertical rectangle of aligned nodes. The mesher is now reproducible: one run is every run.
  mesh::LayeredBlockOptions o;
  o.size_at_site = 40e-6;
  o.size_far = 600e-6;
  const mesh::LayeredBlockResult r = mesh::layered_block_mesh(o);
  const mesh::TetMeshCheck check = mesh::tet_mesh_check(r.mesh);
  EXPECT_TRUE(check.degenerate.empty()) << check.degenerate.size() << " flat tets";
  EXPECT_GT(r.quality[0].min_quality, 0.1);
}
