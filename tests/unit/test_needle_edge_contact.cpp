// The second pass of surface contact (internal fem::detail::NeedleEdgeContact): a needle's points against the tissue's
// deformed top faces. On a structured block whose top is pressed into a valley, a grid of points just under the
// surface: the forces are minus the gradient of the contact energy and the tangent is the gradient of the forces,
// both against central finite differences, with augmented-Lagrangian multipliers from an earlier state. A point
// pressed into the bottom of a valley is held by each face of it; a point above the surface is not held. The
// multipliers, named by their faces' top nodes, carry over to the same surface with its faces renumbered; the faces
// met at a converged state hold a point through the next step, also just outside them under a crease.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "../../src/fem/needle_edge_contact.hpp"
#include "../../src/fem/sparse_pattern.hpp"
#include "../support/gel_block.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::detail;

namespace {
// The gel block with every dof free, its tangent's pattern and a penalty stiffness per top node.
struct Block : test::GelBlock {
  std::vector<int> free_index;
  UpperPattern pattern;
  std::vector<double> stiffness;  // per top node, N/m
};

Block block() {
  Block b{test::gel_block(), {}, {}, {}};
  const int n = static_cast<int>(b.space.nodes.size());
  b.free_index.resize(3 * static_cast<size_t>(n));
  for (int i = 0; i < 3 * n; ++i) b.free_index[static_cast<size_t>(i)] = i;
  b.pattern = upper_pattern(b.space.connectivity, 4, n, b.free_index);
  b.stiffness.assign(b.top.nodes.size(), 2e3);
  return b;
}

// The block spans (-0.5, 0.5) mm in x and y. Its top pressed into a conical valley `depth` deep at (x, y) =
// (0.02, -0.03) mm, 0.3 mm in radius, with a small
// shear.
constexpr double kCentreX = 0.02e-3, kCentreY = -0.03e-3;  // m
Eigen::VectorXd valley(const Block& b, double depth = 40e-6) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(b.space.nodes.size()));
  for (int a : b.top.nodes) {
    const Eigen::Vector3d& x = b.space.nodes[static_cast<size_t>(a)];
    const double r = std::hypot(x.x() - kCentreX, x.y() - kCentreY);
    u[3 * a + 2] = -depth * std::max(0.0, 1 - r / 0.3e-3);
    u[3 * a] = 3e-6 * std::sin(7e3 * x.y());
  }
  return u;
}

struct Evaluation {
  double energy;
  Eigen::VectorXd force;
  std::vector<double> tangent;
};
Evaluation evaluate(NeedleEdgeContact& contact, const Block& b, const Eigen::VectorXd& u, double d) {
  Evaluation e{0, Eigen::VectorXd::Zero(u.size()), std::vector<double>(b.pattern.row_indices.size(), 0.0)};
  e.energy = contact.evaluate(b.space.nodes, u, d, true, true, e.force, b.free_index, b.pattern, e.tangent);
  return e;
}
}  // namespace

TEST(NeedleEdgeContact, ForcesAndTangentAreTheDerivativesOfItsEnergy) {
  const Block b = block();
  const Eigen::VectorXd u = valley(b);
  // A 5 x 5 grid of points 150 µm apart round the valley, each 2 µm under the undeformed surface's valley shape.
  std::vector<Eigen::Vector3d> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) {
      const double x = kCentreX + 0.15e-3 * i + 13e-6, y = kCentreY + 0.15e-3 * j + 7e-6;
      const double r = std::hypot(x - kCentreX, y - kCentreY);
      points.emplace_back(x, y, b.top.z - 40e-6 * std::max(0.0, 1 - r / 0.3e-3) - 2e-6 - 1e-6 * (i + j + 4) / 8);
    }
  NeedleEdgeContact contact(b.top, b.stiffness, points, Eigen::Vector3d(0, 0, -1));
  evaluate(contact, b, u, 0.5e-6);
  contact.augment();  // multipliers from a state half a micrometre further on
  const Evaluation base = evaluate(contact, b, u, 0.0);
  ASSERT_GT(base.energy, 0);
  const double h = 1e-11;  // m
  double force_error = 0, force_scale = 0, tangent_error = 0, tangent_scale = 0;
  for (int a : b.top.nodes)
    for (int c = 0; c < 3; ++c) {
      const int dof = 3 * a + c;
      Eigen::VectorXd up = u, down = u;
      up[dof] += h;
      down[dof] -= h;
      const Evaluation plus = evaluate(contact, b, up, 0.0), minus = evaluate(contact, b, down, 0.0);
      force_error = std::max(force_error, std::abs(-(plus.energy - minus.energy) / (2 * h) - base.force[dof]));
      force_scale = std::max(force_scale, std::abs(base.force[dof]));
      const Eigen::VectorXd column = -(plus.force - minus.force) / (2 * h);  // K = -d(force)/du
      for (int row = 0; row <= dof; ++row) {
        const int64_t first = b.pattern.column_pointers[static_cast<size_t>(dof)];
        const int64_t last = b.pattern.column_pointers[static_cast<size_t>(dof) + 1];
        const bool stored = std::binary_search(b.pattern.row_indices.begin() + first,
                                               b.pattern.row_indices.begin() + last, int64_t{row});
        const double k = stored ? base.tangent[static_cast<size_t>(entry_position(b.pattern, row, dof))] : 0.0;
        tangent_error = std::max(tangent_error, std::abs(column[row] - k));
        tangent_scale = std::max(tangent_scale, std::abs(k));
      }
    }
  ASSERT_GT(force_scale, 0);
  EXPECT_LT(force_error, 1e-6 * force_scale);
  EXPECT_LT(tangent_error, 1e-5 * tangent_scale);
}

TEST(NeedleEdgeContact, APointInAValleyIsHeldByEachOfItsFaces) {
  const Block b = block();
  for (const auto& [depth, under] : {std::pair{40e-6, 1e-6}, std::pair{120e-6, 3e-6}}) {
    const Eigen::VectorXd u = valley(b, depth);
    // The valley's lowest node, and a point under it: every top face round that node holds the point.
    int bottom = b.top.nodes.front();
    for (int a : b.top.nodes)
      if (b.space.nodes[a].z() + u[3 * a + 2] < b.space.nodes[bottom].z() + u[3 * bottom + 2]) bottom = a;
    const Eigen::Vector3d lowest = b.space.nodes[bottom] + u.segment<3>(3 * bottom);
    int faces_round = 0;
    for (const auto& t : b.top.triangles) faces_round += t[0] == bottom || t[1] == bottom || t[2] == bottom;
    NeedleEdgeContact held(b.top, b.stiffness, {lowest - Eigen::Vector3d(0, 0, under)}, Eigen::Vector3d(0, 0, -1));
    const Evaluation e = evaluate(held, b, u, 0.0);
    size_t hash = 0;
    held.hash_active(hash);
    EXPECT_NE(hash, 0u);
    EXPECT_EQ(held.active_pairs(), static_cast<size_t>(faces_round)) << depth;
    EXPECT_GT(held.force_on_needle().z(), 0);  // the needle is pushed out of the valley
    EXPECT_GT(e.energy, 0);
    // Above the valley's bottom the point is free.
    NeedleEdgeContact free(b.top, b.stiffness, {lowest + Eigen::Vector3d(0, 0, 1e-6)}, Eigen::Vector3d(0, 0, -1));
    EXPECT_EQ(evaluate(free, b, u, 0.0).energy, 0.0);
    EXPECT_EQ(free.active_pairs(), 0u);
  }
}

// The multipliers named by their faces' top nodes survive a renumbering of the faces (what a rezoning does): the
// same points against the same surface with its faces in reverse order have the same energy and forces.
TEST(NeedleEdgeContact, MultipliersCarryOverToRenumberedFaces) {
  const Block b = block();
  const Eigen::VectorXd u = valley(b);
  std::vector<Eigen::Vector3d> points;
  for (int i = -2; i <= 2; ++i)
    points.emplace_back(kCentreX + 20e-6 * i + 3e-6, kCentreY + 11e-6 * i, b.top.z - 42e-6 + 2e-6 * std::abs(i));
  NeedleEdgeContact original(b.top, b.stiffness, points, Eigen::Vector3d(0, 0, -1));
  evaluate(original, b, u, 1e-6);
  original.augment();
  ASSERT_FALSE(original.held_pairs().empty());
  TopSurface reversed = b.top;
  std::reverse(reversed.triangles.begin(), reversed.triangles.end());
  NeedleEdgeContact renumbered(reversed, b.stiffness, points, Eigen::Vector3d(0, 0, -1));
  renumbered.set_held_pairs(original.held_pairs());
  const Evaluation a = evaluate(original, b, u, 0.0), c = evaluate(renumbered, b, u, 0.0);
  EXPECT_GT(a.energy, 0);
  EXPECT_NEAR(c.energy, a.energy, 1e-12 * a.energy);
  EXPECT_LT((c.force - a.force).norm(), 1e-12 * a.force.norm());
  // Without them the energy is the penalty's alone, smaller.
  NeedleEdgeContact fresh(reversed, b.stiffness, points, Eigen::Vector3d(0, 0, -1));
  EXPECT_LT(evaluate(fresh, b, u, 0.0).energy, 0.9 * a.energy);
}

// The faces a point was over at the last converged state hold it through the next step: a point 1 µm under a face's
// centroid, moved 110 µm deeper (farther than the 100 µm faces' reach), is held by that face when the pairs were kept
// there, and by none without.
TEST(NeedleEdgeContact, FacesMetAtTheConvergedStateHoldThePointThroughTheStep) {
  const Block b = block();
  const Eigen::VectorXd u = valley(b);
  Eigen::Vector3d point = Eigen::Vector3d::Constant(1.0);
  for (const auto& t : b.top.triangles) {  // under the deformed centroid nearest (x, y) = the valley's centre
    Eigen::Vector3d x[3];
    for (int k = 0; k < 3; ++k) x[k] = b.space.nodes[t[k]] + u.segment<3>(3 * t[k]);
    const Eigen::Vector3d centroid = (x[0] + x[1] + x[2]) / 3;
    const Eigen::Vector3d normal = (x[1] - x[0]).cross(x[2] - x[0]).normalized();
    if (std::hypot(centroid.x() - kCentreX, centroid.y() - kCentreY) <
        std::hypot(point.x() - kCentreX, point.y() - kCentreY))
      point = centroid - 1e-6 * normal;
  }
  NeedleEdgeContact kept(b.top, b.stiffness, {point}, Eigen::Vector3d(0, 0, -1));
  kept.keep_pairs(b.space.nodes, u, 0.0);
  const Evaluation held = evaluate(kept, b, u, 110e-6);
  EXPECT_GT(held.energy, 0);
  EXPECT_GT(kept.force_on_needle().z(), 0);
  EXPECT_GT(kept.max_penetration(), 100e-6);
  NeedleEdgeContact fresh(b.top, b.stiffness, {point}, Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(evaluate(fresh, b, u, 110e-6).energy, 0.0);
}

// A point in a valley's bottom at the converged state, then 30 µm deeper: it lies under the valley's faces but
// outside each of them by more than kMargin, so a fresh search finds none of them; the faces kept from the converged
// state hold it while it stays within kKeptMargin of them (the §6.2 sharp bevel's tip in its crease, twenty-fourth
// session).
TEST(NeedleEdgeContact, FacesKeptFromTheConvergedStateHoldAPointUnderTheirCrease) {
  const Block b = block();
  const Eigen::VectorXd u = valley(b, 120e-6);
  int bottom = b.top.nodes.front();
  for (int a : b.top.nodes)
    if (b.space.nodes[a].z() + u[3 * a + 2] < b.space.nodes[bottom].z() + u[3 * bottom + 2]) bottom = a;
  const Eigen::Vector3d point = b.space.nodes[bottom] + u.segment<3>(3 * bottom) - Eigen::Vector3d(0, 0, 1e-6);
  int faces_round = 0;
  for (const auto& t : b.top.triangles) faces_round += t[0] == bottom || t[1] == bottom || t[2] == bottom;
  NeedleEdgeContact kept(b.top, b.stiffness, {point}, Eigen::Vector3d(0, 0, -1));
  kept.keep_pairs(b.space.nodes, u, 0.0);
  EXPECT_GT(evaluate(kept, b, u, 30e-6).energy, 0);
  EXPECT_EQ(kept.active_pairs(), static_cast<size_t>(faces_round));
  EXPECT_GT(kept.force_on_needle().z(), 0);
  NeedleEdgeContact fresh(b.top, b.stiffness, {point}, Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(evaluate(fresh, b, u, 30e-6).energy, 0.0);
  EXPECT_EQ(fresh.active_pairs(), 0u);
}
