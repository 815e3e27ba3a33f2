// How deep a needle's tip lies inside the tissue (internal fem::detail::NeedleEmbedding): a rigid box needle against
// a structured block of 100 µm cells, at rest and displaced. A needle above the tissue is not embedded; pressed
// 30 µm or 350 µm into the block at rest, by its placement or by its displacement, its tip is embedded by that much
// (its lowest face is 30 or 350 µm under the top surface); with the whole tissue moved below it, it is not.
#include <gtest/gtest.h>

#include "../../src/fem/needle_embedding.hpp"
#include "../support/gel_block.hpp"
#include "../verification/fem_test_support.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::detail;

namespace {
// A 40 x 40 x 300 µm box needle over the block's centre with its lowest face `bottom` above the top plane (m).
Indenter box_needle(const test::GelBlock& b, double bottom) {
  const Eigen::Vector3d centre(3e-6, 7e-6, b.top.z + bottom);  // the block spans (-0.5, 0.5) mm; off the grid lines
  return {test_support::box_surface(centre + Eigen::Vector3d(-20e-6, -20e-6, 0),
                                    centre + Eigen::Vector3d(20e-6, 20e-6, 300e-6)),
          Eigen::Vector3d(0, 0, -1), 0.0};
}

Eigen::VectorXd at_rest(const test::GelBlock& b) {
  return Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(b.space.nodes.size()));
}
}  // namespace

TEST(NeedleEmbedding, ANeedleAboveTheTissueIsNotEmbedded) {
  const test::GelBlock b = test::gel_block();
  const NeedleEmbedding embedding(b.space, b.top, {box_needle(b, 50e-6)}, 20e-6);
  EXPECT_EQ(embedding.deepest(b.space.nodes, at_rest(b), 0.0), 0.0);
}

TEST(NeedleEmbedding, ANeedleInsideTheTissueIsEmbeddedByItsDepthThere) {
  const test::GelBlock b = test::gel_block();
  // Placed 30 or 350 µm into the block, or 50 µm above it and moved 80 or 400 µm along its direction.
  for (const auto& [bottom, d, depth] : {std::tuple{-30e-6, 0.0, 30e-6}, std::tuple{-350e-6, 0.0, 350e-6},
                                         std::tuple{50e-6, 80e-6, 30e-6}, std::tuple{50e-6, 400e-6, 350e-6}}) {
    const NeedleEmbedding embedding(b.space, b.top, {box_needle(b, bottom)}, 20e-6);
    EXPECT_NEAR(embedding.deepest(b.space.nodes, at_rest(b), d), depth, 1e-9 * depth) << bottom << " " << d;
  }
  // The same needle 350 µm in, with the whole tissue moved 500 µm down: above the deformed tissue.
  Eigen::VectorXd down = at_rest(b);
  for (Eigen::Index n = 0; n < down.size() / 3; ++n) down[3 * n + 2] = -500e-6;
  const NeedleEmbedding embedding(b.space, b.top, {box_needle(b, -350e-6)}, 20e-6);
  EXPECT_EQ(embedding.deepest(b.space.nodes, down, 0.0), 0.0);
}
