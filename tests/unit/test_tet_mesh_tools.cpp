// §3.3 data structures and checks on real meshes: face/neighbour links (Table 3.2), a closed boundary surface of
// Euler characteristic 2 that lies on the block's faces only (so the layer interfaces are conforming), layer
// assignment rules, orientation/degeneracy errors, tissue presets and .msh import.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/layer_assignment.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/mesh_validation.hpp"
#include "needlekit/mesh/msh_import.hpp"
#include "needlekit/mesh/tet_adjacency.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

mesh::LayeredBlockOptions block(double height, std::vector<mesh::TissueLayer> layers) {
  mesh::LayeredBlockOptions o;
  o.width = 500e-6;
  o.length = 400e-6;
  o.layers = std::move(layers);
  if (o.layers.empty()) o.layers = {{"tissue", height, 1e5, 0.4}};
  o.size_at_site = 30e-6;
  o.refinement_radius = 60e-6;
  o.size_far = 100e-6;
  o.threads = 1;
  return o;
}

std::vector<mesh::TissueLayer> skin_400um() {
  auto layers = materials::skin_layers();
  layers[2].thickness = 240e-6;
  return layers;
}

const mesh::LayeredBlockResult& skin_block() {
  static const mesh::LayeredBlockResult r = mesh::layered_block_mesh(block(400e-6, skin_400um()));
  return r;
}

mesh::TetMesh unit_tet() {
  mesh::TetMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.tets = {{0, 1, 2, 3}};
  m.tet_layer = {0};
  m.layers = {{"a", 1, 1, 0.3}};
  return m;
}

std::filesystem::path temp_file(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / ("needlekit-msh-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

// Two tetrahedra sharing the face (1, 2, 3) in MSH 2.2, in physical volumes "top" (1) and "bottom" (2).
std::string two_tets_msh(const std::string& second_tet = "1 3 2 5") {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3 1 \"top\"\n3 2 \"bottom\"\n$EndPhysicalNames\n"
         "$Nodes\n5\n1 0 0 0\n2 100 0 0\n3 0 100 0\n4 0 0 100\n5 0 0 -100\n$EndNodes\n"
         "$Elements\n2\n1 4 2 1 1 1 2 3 4\n2 4 2 2 2 " + second_tet + "\n$EndElements\n";
}

}  // namespace

TEST(TetAdjacency, Table32NeighboursOfT1) {
  // §3.3.3's example: T1 = (P1..P4) and T2..T5 on its faces (P1P2P3), (P2P3P4), (P3P4P1), (P4P1P2).
  mesh::TetMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3, 0.3, -1}, {1, 1, 1}, {-1, 0.3, 0.3}, {0.3, -1, 0.3}};
  m.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}, {1, 2, 3, 5}, {2, 3, 0, 6}, {3, 0, 1, 7}};
  const mesh::TetTopology top = mesh::tet_topology(m);
  EXPECT_EQ(top.tet_neighbors[0], (std::array<int, 4>{1, 2, 3, 4}));
  EXPECT_EQ(top.triangles.size(), 4u + 4 * 3);
  EXPECT_EQ(top.boundary_triangles.size(), 4u * 3);
  for (int f = 0; f < 4; ++f) EXPECT_EQ(top.triangle_tets[top.tet_triangles[0][f]][1], f + 1);
}

TEST(TetAdjacency, BlockFacesAreSharedByTwoTetsAndBoundaryIsClosed) {
  const mesh::TetMesh& m = skin_block().mesh;
  const mesh::TetTopology top = mesh::tet_topology(m);
  const std::size_t boundary = top.boundary_triangles.size();
  EXPECT_EQ(4 * m.tets.size(), 2 * (top.triangles.size() - boundary) + boundary);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    for (int f = 0; f < 4; ++f) {
      const int n = top.tet_neighbors[e][f];
      if (n < 0) continue;
      const auto& back = top.tet_neighbors[n];
      EXPECT_NE(std::find(back.begin(), back.end(), static_cast<int>(e)), back.end());
    }
  }
  // Boundary faces lie on the six faces of the block only: no gaps at the layer interfaces (conforming mesh).
  for (int t : top.boundary_triangles) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k : top.triangles[t]) c += m.nodes[k] / 3;
    const bool on_face = std::abs(std::abs(c.x()) - 250e-6) < 1e-12 || std::abs(std::abs(c.y()) - 200e-6) < 1e-12 ||
                         std::abs(c.z()) < 1e-12 || std::abs(c.z() + 400e-6) < 1e-12;
    ASSERT_TRUE(on_face) << "boundary face inside the block at " << c.transpose();
  }
  const mesh::BoundarySurface s = mesh::boundary_surface(m, top);
  EXPECT_EQ(mesh::euler_characteristic(s), 2);
  for (const auto& n : s.neighbors) {
    for (int k = 0; k < 3; ++k) ASSERT_GE(n[k], 0);
  }
  // Outward orientation: the divergence theorem gives the block volume, and the area vectors sum to zero.
  double volume = 0;
  Eigen::Vector3d area_sum = Eigen::Vector3d::Zero();
  for (const auto& t : s.triangles) {
    const Eigen::Vector3d a = m.nodes[t[0]], b = m.nodes[t[1]], c = m.nodes[t[2]];
    const Eigen::Vector3d area = 0.5 * (b - a).cross(c - a);
    volume += area.dot((a + b + c) / 3) / 3;
    area_sum += area;
  }
  EXPECT_NEAR(volume, 500e-6 * 400e-6 * 400e-6, 1e-9 * volume);
  EXPECT_LT(area_sum.norm(), 1e-9 * 500e-6 * 400e-6);
}

TEST(TetAdjacency, FaceSharedByThreeTetsIsRejected) {
  mesh::TetMesh m = unit_tet();
  m.nodes.push_back({0.2, 0.2, -1});
  m.nodes.push_back({0.3, 0.2, -1});
  m.tets.push_back({0, 1, 2, 4});
  m.tets.push_back({0, 2, 1, 5});
  EXPECT_THAT([&] { mesh::tet_topology(m); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("shared by 3 tetrahedra (0, 1, 2, ...)")));
}

TEST(LayerAssignment, ConformingBlockMatchesItsGroupsWithBothRules) {
  const mesh::TetMesh& m = skin_block().mesh;
  EXPECT_EQ(mesh::tet_layers(m, m.layers, {mesh::LayerRule::Nodes}), m.tet_layer);
  EXPECT_EQ(mesh::tet_layers(m, m.layers, {mesh::LayerRule::Centroid}), m.tet_layer);
}

TEST(LayerAssignment, NodeAndCentroidRulesDifferOnlyAcrossInterfaces) {
  // A homogeneous mesh (no interfaces in it) assigned to the §3.3.2 layers.
  const mesh::LayeredBlockResult homogeneous = mesh::layered_block_mesh(block(400e-6, {}));
  const mesh::TetMesh& m = homogeneous.mesh;
  const auto layers = skin_400um();
  const auto by_nodes = mesh::tet_layers(m, layers, {mesh::LayerRule::Nodes});
  const auto by_centroid = mesh::tet_layers(m, layers, {mesh::LayerRule::Centroid});
  const double interfaces[] = {20e-6, 160e-6};
  int differ = 0;
  std::vector<int> count(3, 0);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    ++count[by_nodes[e]];
    double lo = 1, hi = -1;
    for (int k : m.tets[e]) lo = std::min(lo, -m.nodes[k].z()), hi = std::max(hi, -m.nodes[k].z());
    // §3.3.2: SC iff a node lies within 20 um of the surface; DM iff every node is below 160 um.
    EXPECT_EQ(by_nodes[e] == 0, lo < 20e-6);
    EXPECT_EQ(by_nodes[e] == 2, lo >= 160e-6);
    if (by_nodes[e] == by_centroid[e]) continue;
    ++differ;
    EXPECT_LT(by_nodes[e], by_centroid[e]);  // the node rule pulls straddling elements up
    bool straddles = false;
    for (double d : interfaces) straddles = straddles || (lo < d && d < hi);
    EXPECT_TRUE(straddles) << "tet " << e << " spans depths " << lo << " .. " << hi;
  }
  EXPECT_GT(differ, 0);
  for (int c : count) EXPECT_GT(c, 0);
}

TEST(MeshValidation, QualityIsOneForARegularTetAtAnyScaleAndOrientation) {
  const Eigen::Vector3d a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  for (double scale : {1e-6, 1.0, 1e3}) {
    EXPECT_NEAR(mesh::tet_quality(a * scale, b * scale, c * scale, d * scale), 1.0, 1e-12);
    EXPECT_NEAR(mesh::tet_quality(a * scale, c * scale, b * scale, d * scale), 1.0, 1e-12);
  }
  EXPECT_NEAR(std::abs(mesh::signed_volume(a, b, c, d)), 8.0 / 3.0, 1e-12);
  // The unit right-angle corner: r_in = 1/(3+sqrt 3), R = sqrt(3)/2.
  EXPECT_NEAR(mesh::tet_quality({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 3 * (1 / (3 + std::sqrt(3.0))) / (std::sqrt(3.0) / 2), 1e-12);
  EXPECT_EQ(mesh::tet_quality({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}), 0.0);
  EXPECT_DOUBLE_EQ(mesh::signed_volume({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1.0 / 6);  // Fig 3.2
}

TEST(MeshValidation, InvertedAndDegenerateElementsAreNamed) {
  mesh::TetMesh m = unit_tet();
  m.nodes.push_back({0.5, 0.5, 1e-9});
  m.nodes.push_back({1, 1, 1});
  m.tets.push_back({1, 2, 0, 4});   // 1: nearly flat (height 1e-9)
  m.tets.push_back({0, 2, 1, 5});   // 2: left-handed
  m.tet_layer = {0, 0, 0};
  const mesh::TetMeshCheck check = mesh::tet_mesh_check(m);
  EXPECT_EQ(check.inverted, std::vector<int>{2});
  EXPECT_EQ(check.degenerate, std::vector<int>{1});
  EXPECT_FALSE(check.valid());
  EXPECT_THAT([&] { mesh::validate(m, "case.msh"); },
              testing::ThrowsMessage<InvalidInput>(testing::AllOf(
                  HasSubstr("case.msh: 1 inverted (left-handed, negative volume) tetrahedra: 2"),
                  HasSubstr("1 degenerate tetrahedra (quality < 0.0001): 1"))));
  EXPECT_EQ(mesh::reoriented_count(m), 1);
  EXPECT_TRUE(mesh::tet_mesh_check(m).inverted.empty());
  m.tets.push_back({0, 1, 1, 2});
  m.tet_layer.push_back(0);
  EXPECT_THAT([&] { mesh::tet_mesh_check(m); }, testing::ThrowsMessage<InvalidInput>(HasSubstr("tetrahedron 3 repeats node 1")));
}

TEST(TissuePresets, DissertationAndLiteratureValues) {
  EXPECT_EQ(materials::tissue_preset_names(),
            (std::vector<std::string>{"skin", "skin-stiff-sc", "silicone-0.2mpa", "silicone-0.5mpa", "skin-geerligs-2011"}));
  EXPECT_DOUBLE_EQ(materials::tissue_preset("Skin_Stiff_SC").layers[0].youngs_modulus, 1e9);
  const auto phantom = materials::tissue_preset("silicone-0.2mpa");
  ASSERT_EQ(phantom.layers.size(), 1u);
  EXPECT_DOUBLE_EQ(phantom.layers[0].youngs_modulus, 0.2e6);
  EXPECT_DOUBLE_EQ(phantom.layers[0].poisson_ratio, 0.49);
  EXPECT_DOUBLE_EQ(materials::tissue_preset("silicone-0.5mpa").layers[0].youngs_modulus, 0.5e6);
  for (const std::string& name : materials::tissue_preset_names()) {
    const auto p = materials::tissue_preset(name);
    double height = 0;
    for (const auto& l : p.layers) height += l.thickness;
    EXPECT_NEAR(height, p.height, 1e-15) << name;
    EXPECT_FALSE(p.source.empty());
    EXPECT_NO_THROW(materials::validate(p.layers));
  }
  EXPECT_THAT([] { materials::tissue_preset("liver"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("unknown tissue preset 'liver', expected one of: skin,")));
}

TEST(MshImport, PhysicalVolumesBecomeLayers) {
  const auto file = temp_file("two.msh", two_tets_msh());
  mesh::MshImportOptions o;
  o.unit = 1e-6;
  o.layers = {{"bottom", 0, 0.08e6, 0.4}, {"top", 0, 100e6, 0.4}};
  const mesh::MshImportResult r = mesh::msh_import(file, o);
  ASSERT_EQ(r.mesh.tets.size(), 2u);
  EXPECT_EQ(r.mesh.nodes.size(), 5u);
  EXPECT_EQ(r.mesh.layers[0].name, "bottom");
  EXPECT_EQ(r.mesh.tet_layer, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(r.mesh.nodes[1].x(), 100e-6);
  EXPECT_EQ(r.quality[1].tets, 1);
  EXPECT_NEAR(r.quality[1].min_quality, 3 * (1 / (3 + std::sqrt(3.0))) / (std::sqrt(3.0) / 2), 1e-12);
  // Without layers: named after the groups, in the file's order.
  const mesh::MshImportResult named = mesh::msh_import(file, {});
  ASSERT_EQ(named.mesh.layers.size(), 2u);
  EXPECT_EQ(named.mesh.layers[0].name, "top");
}

TEST(MshImport, ClearErrors) {
  const auto file = temp_file("two.msh", two_tets_msh());
  mesh::MshImportOptions o;
  o.layers = {{"top", 0, 1e5, 0.4}, {"dermis", 0, 1e5, 0.4}};
  EXPECT_THAT([&] { mesh::msh_import(file, o); },
              testing::ThrowsMessage<InvalidInput>(testing::AllOf(
                  HasSubstr(file.string() + ": no physical volume group named \"dermis\" (layer 1)"),
                  HasSubstr("the file has \"top\", \"bottom\""))));
  o.layers = {{"top", 0, 1e5, 0.4}};
  EXPECT_THAT([&] { mesh::msh_import(file, o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("1 of the 2 tetrahedra are in the layers")));
  const auto inverted = temp_file("inverted.msh", two_tets_msh("1 2 3 5"));
  EXPECT_THAT([&] { mesh::msh_import(inverted, {}); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr(inverted.string() + ": 1 inverted (left-handed, negative volume) tetrahedra: 1")));
  mesh::MshImportOptions fix;
  fix.reorient = true;
  EXPECT_EQ(mesh::msh_import(inverted, fix).reoriented, 1);
  const auto surface = temp_file("surface.msh",
                                 "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                                 "$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n");
  EXPECT_THAT([&] { mesh::msh_import(surface, {}); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr(surface.string() + ": no tetrahedra")));
  EXPECT_THAT([&] { mesh::msh_import(file.parent_path() / "missing.msh", {}); },
              testing::ThrowsMessage<IoError>(HasSubstr("missing.msh: cannot read")));
  const auto garbage = temp_file("garbage.msh", "this is not a mesh\n");
  EXPECT_THROW(mesh::msh_import(garbage, {}), needlekit::IoError);
}

// Gmsh 4.8 dies with SIGSEGV reading an MSH 2.2 file whose $Nodes count (3) leaves out a node the element uses (found
// by fuzz_gmsh_msh): the read runs in a child process, so the crash is a message naming the file, and the process
// goes on (the same file again, then a good one).
TEST(MshImport, GmshReaderCrashIsBadInput) {
  const auto crashing = temp_file("crashing.msh",
                                  "$MeshFormat\n2.2 0 8\n$EnNames\n$Nodes\n3\n1 0 0 0\n2 100 0 0\n3 0 100 0\n"
                                  "4 0 0 -100\n$EndNodes\n$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n");
  for (int attempt = 0; attempt < 2; ++attempt) {
    EXPECT_THAT([&] { mesh::msh_import(crashing, {}); },
                testing::ThrowsMessage<InvalidInput>(
                    HasSubstr(crashing.string() + ": Gmsh's .msh reader crashed on this file (Segmentation fault)")));
  }
  const auto good = temp_file("good.msh", two_tets_msh());
  mesh::MshImportOptions o;
  o.layers = {{"top", 0, 1e5, 0.4}, {"bottom", 0, 1e5, 0.4}};
  EXPECT_EQ(mesh::msh_import(good, o).mesh.tets.size(), 2u);
}

// Node tags far beyond the node count: a sparse numbering reads as the dense one, and a tag written "-3050" (read by
// Gmsh as 2^64 - 3050; it asked for a table of 2^64 entries and ended the fuzzer with std::length_error, found by
// fuzz_gmsh_msh: tests/data/fuzz-regressions/gmsh_msh/fuzz_gmsh_negative_node_tag_length_error.msh) is looked up
// too, and the file is refused by name for what its tetrahedron then is.
TEST(MshImport, SparseAndHugeNodeTagsAreLookedUpNotTabulated) {
  const std::vector<mesh::TissueLayer> layers = {{"top", 0, 1e5, 0.4}, {"bottom", 0, 1e5, 0.4}};
  mesh::MshImportOptions o;
  o.layers = layers;
  const mesh::MshImportResult dense = mesh::msh_import(temp_file("dense.msh", two_tets_msh()), o);
  std::string sparse_text = two_tets_msh("1000000001 1000000003 1000000002 4000000000000");
  for (const auto& [from, to] : {std::pair{"\n1 0 0 0\n2 100", "\n1000000001 0 0 0\n1000000002 100"},
                                 std::pair{"\n3 0 100 0\n", "\n1000000003 0 100 0\n"},
                                 std::pair{"\n5 0 0 -100\n", "\n4000000000000 0 0 -100\n"},
                                 std::pair{"1 1 1 2 3 4\n", "1 1 1000000001 1000000002 1000000003 4\n"}})
    sparse_text.replace(sparse_text.find(from), std::string(from).size(), to);
  const mesh::MshImportResult sparse = mesh::msh_import(temp_file("sparse.msh", sparse_text), o);
  ASSERT_EQ(sparse.mesh.tets.size(), dense.mesh.tets.size());  // Gmsh lists the nodes by tag: compare corners
  for (std::size_t t = 0; t < dense.mesh.tets.size(); ++t)
    for (int a = 0; a < 4; ++a)
      EXPECT_EQ(sparse.mesh.nodes[sparse.mesh.tets[t][a]], dense.mesh.nodes[dense.mesh.tets[t][a]]) << t << " " << a;
  const std::filesystem::path negative =
      std::filesystem::path(NEEDLEKIT_TEST_DATA_DIR) / "fuzz-regressions/gmsh_msh/fuzz_gmsh_negative_node_tag_length_error.msh";
  o.layers.clear();
  EXPECT_THAT([&] { mesh::msh_import(negative, o); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("tetrahedron 0 repeats node 0")));
}

// reader_cpu_limit: a node block whose count is read as 10^8 (a malformed file of 78 bytes) makes Gmsh's MSH 4.1
// reader allocate and loop for seconds (14.6 s under ASan); with a limit the file is refused by name once its reader
// has spent the limit, and a well-formed file still reads.
TEST(MshImport, ReaderCpuLimitRefusesAFileThatMakesGmshsReaderLoop) {
  const auto looping = temp_file("looping.msh",
                                 "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 100000000 1 100000000\n$EndNodes\n");
  mesh::MshImportOptions limited;
  limited.reader_cpu_limit = 0.2;
  EXPECT_THAT([&] { mesh::msh_import(looping, limited); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr(
                  looping.string() + ": Gmsh's .msh reader used up its 0.2 s of CPU time on this file")));
  limited.layers = {{"top", 0, 1e5, 0.4}, {"bottom", 0, 1e5, 0.4}};
  limited.reader_cpu_limit = 30;
  EXPECT_EQ(mesh::msh_import(temp_file("good.msh", two_tets_msh()), limited).mesh.tets.size(), 2u);
  limited.reader_cpu_limit = -1;
  EXPECT_THAT([&] { mesh::msh_import(looping, limited); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("reader_cpu_limit = -1 s; expected 0 (none)")));
}

// keep_reader_process: the child that runs Gmsh's reader serves several files, and a file that crashes Gmsh's reader
// (tests/data/fuzz-regressions/gmsh_msh) is that file's error only: the next file gets a fresh child and is read.
TEST(MshImport, KeptReaderProcessIsReplacedAfterACrash) {
  const auto file = temp_file("two.msh", two_tets_msh());
  const auto crash = temp_file("crash.msh",
                               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 100 0 0\n3 0 100 0\n"
                               "4 0 0 -100\n$EndNodes\n$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n");
  mesh::MshImportOptions keep;
  keep.keep_reader_process = true;
  const mesh::MshImportResult once = mesh::msh_import(file, {});
  for (int round = 0; round < 2; ++round) {
    const mesh::MshImportResult kept = mesh::msh_import(file, keep);
    EXPECT_EQ(kept.mesh.tets, once.mesh.tets);
    ASSERT_EQ(kept.mesh.nodes.size(), once.mesh.nodes.size());
    for (std::size_t i = 0; i < once.mesh.nodes.size(); ++i) EXPECT_EQ(kept.mesh.nodes[i], once.mesh.nodes[i]);
    EXPECT_THAT([&] { mesh::msh_import(crash, keep); },
                testing::ThrowsMessage<InvalidInput>(HasSubstr(crash.string() + ": Gmsh's .msh reader crashed")));
  }
  EXPECT_EQ(mesh::msh_import(file, keep).mesh.tets.size(), 2u);
}
