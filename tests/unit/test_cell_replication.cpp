// An array's block assembled from copies of one meshed cell (mesh/cell_replication.hpp, issue 36 item 5), square
// (a needle's cell) and hexagonal (a pair of rows): it is conforming (every interior face shared by two tetrahedra,
// the boundary only on the block's six faces), has no duplicate nodes, fills the block's volume layer by layer, gives
// every needle the same nodes under its tip, is the same on one and two threads, is mirror symmetric where the
// square array is (its quarter model a part of it), and falls back to the whole block, saying why, where cells do not
// fit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

#include "needlekit/mesh/cell_replication.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/mesh_validation.hpp"
#include "needlekit/mesh/tet_adjacency.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

constexpr double kPitch = 300e-6;
const mesh::CellLattice kSquare = mesh::square_lattice(kPitch);

// A two-layer block (100 um over 200 um) holding a columns x rows square array of `kPitch` with `margin` of tissue
// beyond the outermost cells, meshed coarsely enough to take about a second.
mesh::LayeredBlockOptions array_block(int columns, int rows, double margin) {
  mesh::LayeredBlockOptions o;
  o.width = columns * kPitch + 2 * margin;
  o.length = rows * kPitch + 2 * margin;
  o.layers = {{"epidermis", 100e-6, 1e6, 0.4}, {"dermis", 200e-6, 0.1e6, 0.4}};
  o.size_at_site = 25e-6;
  o.refinement_radius = 40e-6;
  o.size_far = 100e-6;
  o.site_circle_radius = 20e-6;
  o.insertion_sites.clear();
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      o.insertion_sites.emplace_back((i - 0.5 * (columns - 1)) * kPitch, (j - 0.5 * (rows - 1)) * kPitch);
    }
  }
  return o;
}

// A two-layer block holding a columns x rows hexagonal array of `kPitch` (rows kPitch*sqrt(3)/2 apart, odd rows
// shifted by +kPitch/2, as insertion::array_positions places them) with `margin` beyond the needles' extent.
mesh::LayeredBlockOptions hexagonal_block(int columns, int rows, double margin) {
  mesh::LayeredBlockOptions o = array_block(1, 1, 0.0);
  const double row = kPitch * std::sqrt(3.0) / 2;
  o.insertion_sites.clear();
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      o.insertion_sites.emplace_back((i - 0.5 * (columns - 1)) * kPitch + (j % 2 == 1 ? 0.25 : -0.25) * kPitch,
                                     (j - 0.5 * (rows - 1)) * row);
    }
  }
  o.width = columns * kPitch + 2 * margin;  // the cells' extent (columns pitches) plus the margin
  o.length = rows * row + 2 * margin;
  return o;
}

// The number of node pairs closer than `distance` (hashing the nodes into cubes of that size).
int close_node_pairs(const std::vector<Eigen::Vector3d>& nodes, double distance) {
  std::unordered_map<std::int64_t, std::vector<int>> cubes;
  const auto cube = [&](const Eigen::Vector3d& p) { return (p.array() / distance).floor().cast<std::int64_t>(); };
  const auto key = [](const Eigen::Array<std::int64_t, 3, 1>& c) { return (c.x() * 1000003 + c.y()) * 1000003 + c.z(); };
  for (std::size_t i = 0; i < nodes.size(); ++i) cubes[key(cube(nodes[i]))].push_back(static_cast<int>(i));
  int pairs = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto c = cube(nodes[i]);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cubes.find(key(c + Eigen::Array<std::int64_t, 3, 1>(dx, dy, dz)));
          if (it == cubes.end()) continue;
          for (int j : it->second) pairs += j > static_cast<int>(i) && (nodes[j] - nodes[i]).norm() < distance;
        }
  }
  return pairs;
}

// Conforming, no duplicate nodes, right-handed, every layer's volume the block's, the boundary only on the block's
// faces.
void expect_conforming_block(const mesh::TetMesh& m, const mesh::LayeredBlockOptions& o) {
  const mesh::TetTopology topology = mesh::tet_topology(m);  // throws for a face of more than two tetrahedra
  const double height = o.layers[0].thickness + o.layers[1].thickness, tolerance = 1e-9 * kPitch;
  int off_boundary = 0;
  for (int b : topology.boundary_triangles) {
    bool on_a_face = false;
    for (int axis = 0; axis < 3; ++axis) {
      const double low = axis == 0 ? -0.5 * o.width : axis == 1 ? -0.5 * o.length : -height;
      const double high = axis == 0 ? 0.5 * o.width : axis == 1 ? 0.5 * o.length : 0.0;
      for (double plane : {low, high}) {
        bool all = true;
        for (int n : topology.triangles[static_cast<std::size_t>(b)]) all &= std::abs(m.nodes[n][axis] - plane) < tolerance;
        on_a_face |= all;
      }
    }
    off_boundary += !on_a_face;
  }
  EXPECT_EQ(off_boundary, 0) << "boundary triangles inside the block: faces that do not conform";
  EXPECT_EQ(close_node_pairs(m.nodes, 1e-3 * o.size_at_site), 0) << "duplicate nodes";
  std::vector<double> volume(2, 0.0);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const auto& t = m.tets[e];
    const double v = mesh::signed_volume(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
    ASSERT_GT(v, 0) << "tet " << e;
    volume[static_cast<std::size_t>(m.tet_layer[e])] += v;
  }
  for (int i = 0; i < 2; ++i) {
    const double expected = o.width * o.length * o.layers[static_cast<std::size_t>(i)].thickness;
    EXPECT_NEAR(volume[static_cast<std::size_t>(i)], expected, 1e-9 * expected) << o.layers[static_cast<std::size_t>(i)].name;
  }
}

// The nodes within `radius` of the top surface's point `site`, relative to it.
std::vector<Eigen::Vector3d> nodes_near(const mesh::TetMesh& m, const Eigen::Vector2d& site, double radius) {
  std::vector<Eigen::Vector3d> near;
  const Eigen::Vector3d s(site.x(), site.y(), 0);
  for (const Eigen::Vector3d& p : m.nodes) {
    if ((p - s).norm() < radius) near.push_back(p - s);
  }
  return near;
}

// The largest distance from a point of `points` to its nearest point of `reference`.
double farthest_from(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& reference) {
  double farthest = 0;
  for (const Eigen::Vector3d& p : points) {
    double nearest = 1.0;
    for (const Eigen::Vector3d& q : reference) nearest = std::min(nearest, (p - q).norm());
    farthest = std::max(farthest, nearest);
  }
  return farthest;
}

std::uint64_t coordinate_hash(const mesh::TetMesh& m) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the coordinates' bits and the connectivity
  const auto mix = [&](std::uint64_t v) { h = (h ^ v) * 1099511628211ull; };
  for (const Eigen::Vector3d& p : m.nodes) {
    for (int k = 0; k < 3; ++k) {
      std::uint64_t bits;
      std::memcpy(&bits, &p[k], sizeof bits);
      mix(bits);
    }
  }
  for (const auto& t : m.tets) for (int n : t) mix(static_cast<std::uint64_t>(n));
  return h;
}

}  // namespace

TEST(CellReplication, ThreeByThreeArrayIsConformingAndFillsTheBlock) {
  const mesh::LayeredBlockOptions o = array_block(3, 3, 150e-6);
  const mesh::ArrayBlockMesh r = mesh::array_block_mesh(o, kSquare);
  ASSERT_EQ(r.meshing, mesh::BlockMeshing::ReplicatedCell) << r.reason;
  expect_conforming_block(r.block.mesh, o);
  // Every needle sees the same nodes under its tip, to rounding: a node on the site and the same set around it.
  const std::vector<Eigen::Vector3d> first = nodes_near(r.block.mesh, o.insertion_sites[0], 60e-6);
  ASSERT_GT(first.size(), 10u);
  for (const Eigen::Vector2d& site : o.insertion_sites) {
    const std::vector<Eigen::Vector3d> near = nodes_near(r.block.mesh, site, 60e-6);
    ASSERT_EQ(near.size(), first.size());
    // From a node near this site to the nearest node of the same offset near the first site.
    EXPECT_LT(farthest_from(near, first), 1e-12) << "site (" << site.x() << ", " << site.y() << ")";
    EXPECT_EQ(nodes_near(r.block.mesh, site, 1e-9).size(), 1u) << "no node on the site";
  }
}

TEST(CellReplication, ArrayWithoutMarginOnTwoSidesAsAQuarterModelHasIt) {
  // The quarter model of a 4 x 4 array: its planes x = min and y = min pass between the needles, on the cells' faces.
  mesh::LayeredBlockOptions o = array_block(2, 2, 0.0);
  const double margin = 120e-6;
  o.width += margin, o.length += margin;
  for (Eigen::Vector2d& s : o.insertion_sites) s -= Eigen::Vector2d(0.5 * margin, 0.5 * margin);
  const mesh::ArrayBlockMesh r = mesh::array_block_mesh(o, kSquare);
  ASSERT_EQ(r.meshing, mesh::BlockMeshing::ReplicatedCell) << r.reason;
  expect_conforming_block(r.block.mesh, o);
}

TEST(CellReplication, SameMeshOnOneAndTwoThreads) {
  mesh::LayeredBlockOptions o = array_block(2, 3, 100e-6);
  o.threads = 1;
  const mesh::ArrayBlockMesh one = mesh::array_block_mesh(o, kSquare);
  o.threads = 2;
  const mesh::ArrayBlockMesh two = mesh::array_block_mesh(o, kSquare);
  ASSERT_EQ(one.meshing, mesh::BlockMeshing::ReplicatedCell);
  EXPECT_EQ(one.block.mesh.nodes.size(), two.block.mesh.nodes.size());
  EXPECT_EQ(one.block.mesh.tets.size(), two.block.mesh.tets.size());
  EXPECT_EQ(coordinate_hash(one.block.mesh), coordinate_hash(two.block.mesh));
}

TEST(CellReplication, TheCellIsMeshedOnceWhateverTheArraysSize) {
  // Without margins the block is only copies of the cell, meshed the same for 2 x 2 and 3 x 2 cells: 4 and 6 times
  // its tetrahedra; the nodes shared by neighbouring copies are merged (fewer than 6 cells' worth).
  const mesh::LayeredBlockOptions three_by_two = array_block(3, 2, 0.0), two_by_two = array_block(2, 2, 0.0);
  const mesh::ArrayBlockMesh r32 = mesh::array_block_mesh(three_by_two, kSquare);
  const mesh::ArrayBlockMesh r22 = mesh::array_block_mesh(two_by_two, kSquare);
  ASSERT_EQ(r32.meshing, mesh::BlockMeshing::ReplicatedCell);
  ASSERT_EQ(r22.meshing, mesh::BlockMeshing::ReplicatedCell);
  EXPECT_EQ(r32.block.mesh.tets.size() * 4, r22.block.mesh.tets.size() * 6);
  EXPECT_LT(r32.block.mesh.nodes.size() * 4, r22.block.mesh.nodes.size() * 6);
  expect_conforming_block(r32.block.mesh, three_by_two);
}

// A quarter model of a 3 x 3 array: the symmetry plane x = min runs through the first column of needles.
mesh::LayeredBlockOptions needles_on_the_minus_x_edge() {
  mesh::LayeredBlockOptions o = array_block(3, 3, 0.0);
  o.width -= 0.5 * kPitch;
  for (Eigen::Vector2d& s : o.insertion_sites) s.x() -= 0.25 * kPitch;
  return o;
}

// Without circles round the needles, such a block is framed from needle to needle: the needles on the cells' corners.
TEST(CellReplication, ReducedModelThroughAColumnOfNeedlesIsFramedFromNeedleToNeedle) {
  mesh::LayeredBlockOptions o = needles_on_the_minus_x_edge();
  o.site_circle_radius = 0;
  const mesh::SiteGridCheck grid = mesh::site_grid(o, kSquare);
  ASSERT_TRUE(grid.grid) << grid.reason;
  EXPECT_TRUE(grid.grid->sites_on_corners);
  EXPECT_EQ(grid.grid->columns, 2);
  EXPECT_EQ(grid.grid->rows, 2);
  EXPECT_EQ(grid.grid->margin_left, 0.0);
  const mesh::ArrayBlockMesh r = mesh::array_block_mesh(o, kSquare);
  ASSERT_EQ(r.meshing, mesh::BlockMeshing::ReplicatedCell) << r.reason;
  expect_conforming_block(r.block.mesh, o);
  // Every needle has a node on its site. (The needles do not all see the same mesh: round a needle on the cells'
  // outer corners the margin strips meet the cells.)
  for (const Eigen::Vector2d& site : o.insertion_sites) {
    EXPECT_EQ(nodes_near(r.block.mesh, site, 1e-9).size(), 1u) << site.transpose();
  }
}

// The nodes of m in the box [low, high] of x and y (m), moved by `shift`.
std::vector<Eigen::Vector3d> nodes_in(const mesh::TetMesh& m, const Eigen::Vector2d& low, const Eigen::Vector2d& high,
                                      const Eigen::Vector2d& shift) {
  std::vector<Eigen::Vector3d> inside;
  const double tolerance = 1e-9 * kPitch;
  for (Eigen::Vector3d p : m.nodes) {
    p.head<2>() += shift;
    const Eigen::Array2d xy = p.head<2>().array();
    if ((xy >= low.array() - tolerance).all() && (xy <= high.array() + tolerance).all()) inside.push_back(p);
  }
  return inside;
}

// Without circles, a square array's cell is mirrored from its quadrant (src/mesh/mirrored_cell.hpp): the block is as
// symmetric as the array, and the quarter model through the middle row and column (its cells framed from needle to
// needle) is the full model's quarter, node for node.
TEST(CellReplication, SquareArrayIsMirrorSymmetricAndItsQuarterIsItsQuarter) {
  mesh::LayeredBlockOptions full = array_block(3, 3, 150e-6);
  full.site_circle_radius = 0;
  const mesh::ArrayBlockMesh whole = mesh::array_block_mesh(full, kSquare);
  ASSERT_EQ(whole.meshing, mesh::BlockMeshing::ReplicatedCell) << whole.reason;
  expect_conforming_block(whole.block.mesh, full);
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<Eigen::Vector3d> mirrored = whole.block.mesh.nodes;
    for (Eigen::Vector3d& p : mirrored) p[axis] = -p[axis];
    EXPECT_LT(farthest_from(mirrored, whole.block.mesh.nodes), 1e-12) << "mirrored across axis " << axis;
  }

  mesh::LayeredBlockOptions quarter = full;
  quarter.width = 0.5 * full.width;
  quarter.length = 0.5 * full.length;
  const Eigen::Vector2d shift(0.25 * full.width, 0.25 * full.length);  // from the quarter's frame to the full one's
  quarter.insertion_sites.clear();
  for (const Eigen::Vector2d& s : full.insertion_sites) {
    if (s.x() >= 0 && s.y() >= 0) quarter.insertion_sites.push_back(s - shift);
  }
  const mesh::ArrayBlockMesh part = mesh::array_block_mesh(quarter, kSquare);
  ASSERT_EQ(part.meshing, mesh::BlockMeshing::ReplicatedCell) << part.reason;
  EXPECT_TRUE(mesh::site_grid(quarter, kSquare).grid->sites_on_corners);
  expect_conforming_block(part.block.mesh, quarter);
  const Eigen::Vector2d low(0, 0), high(0.5 * full.width, 0.5 * full.length);  // the whole quarter x, y >= 0
  const std::vector<Eigen::Vector3d> in_full = nodes_in(whole.block.mesh, low, high, Eigen::Vector2d::Zero());
  const std::vector<Eigen::Vector3d> in_part = nodes_in(part.block.mesh, low, high, shift);
  EXPECT_EQ(in_full.size(), in_part.size());
  EXPECT_EQ(in_part.size(), part.block.mesh.nodes.size());
  EXPECT_EQ(4 * part.block.mesh.tets.size(), whole.block.mesh.tets.size());
  EXPECT_LT(farthest_from(in_part, in_full), 1e-12);
  EXPECT_LT(farthest_from(in_full, in_part), 1e-12);
}

TEST(CellReplication, FallsBackToTheWholeBlockAndSaysWhy) {
  mesh::LayeredBlockOptions hexagonal = array_block(2, 2, 150e-6);
  hexagonal.insertion_sites[2].x() += 0.5 * kPitch;  // the second row shifted by half a pitch
  hexagonal.insertion_sites[3].x() += 0.5 * kPitch;
  hexagonal.width += kPitch;
  mesh::SiteGridCheck check = mesh::site_grid(hexagonal, kSquare);
  EXPECT_FALSE(check.grid);
  EXPECT_THAT(check.reason, HasSubstr("off the lattice's grid"));

  // Needles on the block's edge with circles round them: centred cells would leave the block, and with the needles
  // on the cells' corners the circles would cross the cells' faces (the whole block refuses such circles too).
  const mesh::LayeredBlockOptions on_edge = needles_on_the_minus_x_edge();
  check = mesh::site_grid(on_edge, kSquare);
  EXPECT_FALSE(check.grid);
  EXPECT_THAT(check.reason, HasSubstr("leave the block"));
  EXPECT_THAT(check.reason, HasSubstr("circles would cross"));

  mesh::LayeredBlockOptions thin = array_block(2, 2, 5e-6);
  EXPECT_THAT(mesh::site_grid(thin, kSquare).reason, HasSubstr("thinner than half the tip size"));
  mesh::LayeredBlockOptions single = array_block(1, 1, 150e-6);
  EXPECT_THAT(mesh::site_grid(single, kSquare).reason, HasSubstr("single site"));
}

TEST(CellReplication, HexagonalArrayIsConformingAndEveryNeedleSeesItsRowsMesh) {
  // 3 columns x 4 rows: 3 x 2 cells of two needles each (a pitch by pitch*sqrt(3)).
  const mesh::LayeredBlockOptions o = hexagonal_block(3, 4, 120e-6);
  const mesh::ArrayBlockMesh r = mesh::array_block_mesh(o, mesh::hexagonal_lattice(kPitch));
  ASSERT_EQ(r.meshing, mesh::BlockMeshing::ReplicatedCell) << r.reason;
  expect_conforming_block(r.block.mesh, o);
  // Every needle of an even row sees the first needle's nodes around its tip, every needle of an odd row the
  // second's: the same place in the cell. Each has a node on its site.
  for (int parity = 0; parity < 2; ++parity) {
    const std::vector<Eigen::Vector3d> first = nodes_near(r.block.mesh, o.insertion_sites[3 * parity], 60e-6);
    ASSERT_GT(first.size(), 10u);
    for (std::size_t k = 0; k < o.insertion_sites.size(); ++k) {
      if (static_cast<int>(k / 3) % 2 != parity) continue;
      const Eigen::Vector2d& site = o.insertion_sites[k];
      const std::vector<Eigen::Vector3d> near = nodes_near(r.block.mesh, site, 60e-6);
      ASSERT_EQ(near.size(), first.size()) << k;
      EXPECT_LT(farthest_from(near, first), 1e-12) << "needle " << k;
      EXPECT_EQ(nodes_near(r.block.mesh, site, 1e-9).size(), 1u) << "no node on needle " << k;
    }
  }
}

TEST(CellReplication, HexagonalArrayIsTheSameOnOneAndTwoThreads) {
  mesh::LayeredBlockOptions o = hexagonal_block(2, 2, 100e-6);
  o.threads = 1;
  const mesh::ArrayBlockMesh one = mesh::array_block_mesh(o, mesh::hexagonal_lattice(kPitch));
  o.threads = 2;
  const mesh::ArrayBlockMesh two = mesh::array_block_mesh(o, mesh::hexagonal_lattice(kPitch));
  ASSERT_EQ(one.meshing, mesh::BlockMeshing::ReplicatedCell) << one.reason;
  EXPECT_EQ(coordinate_hash(one.block.mesh), coordinate_hash(two.block.mesh));
}

// An odd number of rows: the cells hold the row pairs, and the last row (the first row of a pair with no second) lies
// in the +y margin strip, copied along x like the cell. Before, such an array was meshed whole.
TEST(CellReplication, HexagonalArrayOfAnOddNumberOfRowsHasItsLastRowInTheMarginStrip) {
  const mesh::LayeredBlockOptions o = hexagonal_block(3, 3, 120e-6);
  const mesh::SiteGridCheck grid = mesh::site_grid(o, mesh::hexagonal_lattice(kPitch));
  ASSERT_TRUE(grid.grid) << grid.reason;
  EXPECT_EQ(grid.grid->rows, 1);
  EXPECT_EQ(grid.grid->columns, 3);
  ASSERT_EQ(grid.grid->top_row_sites.size(), 1u);
  EXPECT_NEAR(grid.grid->top_row_sites[0].y(), 0.75 * kPitch * std::sqrt(3.0), 1e-12);
  const mesh::ArrayBlockMesh r = mesh::array_block_mesh(o, mesh::hexagonal_lattice(kPitch));
  ASSERT_EQ(r.meshing, mesh::BlockMeshing::ReplicatedCell) << r.reason;
  expect_conforming_block(r.block.mesh, o);
  // The last row's needles are copies of one another: the same nodes round each tip, and a node on each site.
  const std::vector<Eigen::Vector3d> first = nodes_near(r.block.mesh, o.insertion_sites[6], 60e-6);
  ASSERT_GT(first.size(), 10u);
  for (std::size_t k = 6; k < 9; ++k) {
    const std::vector<Eigen::Vector3d> near = nodes_near(r.block.mesh, o.insertion_sites[k], 60e-6);
    ASSERT_EQ(near.size(), first.size()) << k;
    EXPECT_LT(farthest_from(near, first), 1e-12) << "needle " << k;  // positions relative to the sites
    EXPECT_EQ(nodes_near(r.block.mesh, o.insertion_sites[k], 1e-9).size(), 1u) << "no node on needle " << k;
  }
  // One row only is not a cell: meshed whole, saying why.
  const mesh::SiteGridCheck single_row =
      mesh::site_grid(hexagonal_block(3, 1, 120e-6), mesh::hexagonal_lattice(kPitch));
  EXPECT_FALSE(single_row.grid);
  EXPECT_THAT(single_row.reason, HasSubstr("do not fill a cell"));
}
