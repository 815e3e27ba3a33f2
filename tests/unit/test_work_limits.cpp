// Work that would exceed a limit of core/limits.hpp is refused before it starts, with the estimate and the key that
// raises the limit (issue 16): a 1 m block meshed at 1 um, a design space of 0.01 um steps, a geodesic on a cube with
// one far vertex, absurd layer thicknesses; and the tetrahedron estimate agrees with Gmsh's count.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <cmath>
#include <string>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/geometry/geodesic_distance.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/tet_count_estimate.hpp"

namespace needlekit {
namespace {

using testing::HasSubstr;

void expect_invalid(const std::function<void()>& run, const std::vector<std::string>& parts) {
  try {
    run();
    ADD_FAILURE() << "not refused";
  } catch (const InvalidInput& e) {
    for (const auto& part : parts) EXPECT_THAT(e.what(), HasSubstr(part));
  }
}

TEST(TetCountEstimate, IsWithinAFactorOfTwoOfGmsh) {
  // Blocks with a site, with thin-layer caps and a graded field: the count Gmsh makes against the estimate.
  std::vector<mesh::LayeredBlockOptions> blocks(3);
  blocks[0].layers = {{"a", 600e-6, 1e6, 0.4}};
  blocks[0].width = blocks[0].length = 1500e-6;
  blocks[0].size_at_site = 40e-6;
  blocks[0].size_far = 200e-6;
  blocks[1] = blocks[0];
  blocks[1].layers = {{"thin", 40e-6, 1e6, 0.4}, {"rest", 560e-6, 1e6, 0.4}};
  blocks[2] = blocks[0];
  blocks[2].insertion_sites = {{-300e-6, 0}, {300e-6, 0}};
  blocks[2].refinement_radius = 100e-6;
  for (const auto& block : blocks) {
    const double estimate = mesh::estimated_tetrahedra(block);
    const double gmsh = static_cast<double>(mesh::layered_block_mesh(block).mesh.tets.size());
    EXPECT_GT(estimate, 0.5 * gmsh) << "Gmsh " << gmsh;
    EXPECT_LT(estimate, 2.0 * gmsh) << "Gmsh " << gmsh;
  }
}

TEST(TetCountEstimate, AOneMetreBlockAtOneMicrometreIsRefusedAtOnce) {
  mesh::LayeredBlockOptions block;
  block.width = block.length = 1.0;
  block.layers = {{"slab", 1.0, 1e6, 0.4}};
  block.size_at_site = 1e-6;
  block.size_far = 1e-6;
  EXPECT_NEAR(mesh::estimated_tetrahedra(block), mesh::kTetsPerCubicSize * 1e18, 1e-6 * 6e18);
  const auto start = std::chrono::steady_clock::now();
  expect_invalid([&] { mesh::layered_block_mesh(block); }, {"about 6e+18 tetrahedra", "[mesh] max_tetrahedra"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  // The same block within a raised limit passes the check (and would mesh): the limit is the only obstacle.
  block.size_at_site = block.size_far = 0.2;
  block.refinement_radius = 0.1;
  block.max_tetrahedra = 1e3;
  EXPECT_LT(mesh::estimated_tetrahedra(block), 1e3);
}

TEST(TetCountEstimate, AbsurdLayerThicknessesAreRefusedByName) {
  mesh::LayeredBlockOptions block;
  block.layers = materials::skin_layers();
  block.layers[0].thickness = 1e-11;  // 1e-5 um: OpenCASCADE found no top surface
  block.thin_layer_size_factor = 0;
  expect_invalid([&] { mesh::layered_block_mesh(block); }, {"layer 'stratum corneum' thickness", "below 1e-05"});
  block.layers[0].thickness = 20e-6;
  block.layers[2].thickness = 0.01;  // a 1 cm dermis under a 20 x 20 cm block
  block.width = block.length = 0.2;
  expect_invalid([&] { mesh::layered_block_mesh(block); }, {"tetrahedra", "max_tetrahedra"});
}

TEST(OptimizerLimits, HugeSpacesAreRefusedBeforeAnyWork) {
  analysis::DesignSpace space = analysis::figure_6_20_space(needle::Shape::Cone, false);
  // 0.01 um steps for D1 and D2: the certified method's tables grew to 10 GB (issue 16).
  space.tip_diameter.step = 0.01e-6;
  space.base_diameter.step = 0.01e-6;
  analysis::OptimizerOptions certified;
  certified.method = analysis::SearchMethod::Certified;
  const double bytes = analysis::optimizer_memory_bytes(space, certified.method);
  EXPECT_GT(bytes, 12001.0 * 27001 * 88);
  expect_invalid([&] { analysis::optimize_design(space, certified); },
                 {"GiB (12001 D1 x 27001 D2 values)", "--max-memory-gib"});
  // Without --certified: the number of grid points and the option that raises the limit.
  space.tip_diameter.step = 1e-6;
  space.base_diameter.step = 1e-6;
  space.width.step = 1e-6;
  space.length.step = 1e-6;  // 6.9e11 points
  expect_invalid([&] { analysis::optimize_design(space); }, {"--certified", "--max-grid-points"});
  // The 1 um certified example stays well inside both limits.
  EXPECT_LT(analysis::optimizer_memory_bytes(space, certified.method), 1e8);
}

TEST(GeodesicLimits, ACubeWithOneFarVertexEndsWithinTheWorkBudget) {
  // issue 16: `surface --geodesic` spun for minutes on this cube.
  geometry::TriangleMesh cube = test::cube_mesh(1.0);
  cube.vertices[7] *= 1e6;
  const geometry::SurfaceMesh surface(cube);
  geometry::GeodesicDistanceOptions options;
  options.max_crossings = 100'000;
  const auto d = geometry::geodesic_distance(surface, geometry::vertex_location(surface, 0),
                                             geometry::vertex_location(surface, 6), options);
  EXPECT_GE(d.distance, d.euclidean * (1 - 1e-9)) << geometry::to_string(d.status) << " " << d.reason;
  EXPECT_LE(d.path.triangles.size(), 12u + 16u);  // a trace is cut at the mesh's triangle count
  if (d.status != geometry::DistanceStatus::Converged) EXPECT_THAT(d.reason, HasSubstr("max_crossings"));
  EXPECT_THROW(geometry::geodesic_distance(surface, geometry::vertex_location(surface, 0),
                                           geometry::vertex_location(surface, 6), {.max_crossings = 0}),
               InvalidInput);
}

}  // namespace
}  // namespace needlekit
