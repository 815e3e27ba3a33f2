// Implausible scales are warnings that name the value, the plausible range and the likely unit mistake (one test per
// warning of io/scale_warnings.hpp), and a depth through the tissue block is refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/plausible_scale.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/scale_warnings.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/patch/patch_design.hpp"

namespace {

using namespace needlekit;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::IsEmpty;

needle::NeedleGeometry cylinder(double diameter, double length) {
  return {needle::Shape::Cylinder, diameter, diameter, 0.0, length};
}

// A square of side `size` (m) in the plane z = 0, as two triangles per cell of an n x n grid.
geometry::TriangleMesh square(double size, int n) {
  geometry::TriangleMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) mesh.vertices.emplace_back(size * i / n, size * j / n, 0.0);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = i + (n + 1) * j, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  }
  return mesh;
}

TEST(PlausibleScale, NamesTheValueTheRangeAndTheLikelyUnit) {
  EXPECT_FALSE(units::implausible_length("needle.length", 400e-6, 20e-6, 5e-3));
  const auto long_needle = units::implausible_length("needle.length", 0.4, 20e-6, 5e-3);  // "400 mm"
  ASSERT_TRUE(long_needle);
  EXPECT_THAT(*long_needle, HasSubstr("needle.length is 400 mm, outside the plausible 20 um to 5 mm"));
  EXPECT_THAT(*long_needle, HasSubstr("1000x smaller it would be 400 um"));
  const auto short_needle = units::implausible_length("needle.length", 4e-6, 20e-6, 5e-3);
  ASSERT_TRUE(short_needle);
  EXPECT_THAT(*short_needle, HasSubstr("1000x larger it would be 4 mm"));
}

TEST(ScaleWarnings, ANeedleLongerThan5mmOrShorterThan20um) {
  EXPECT_THAT(io::needle_scale_warnings(cylinder(70e-6, 400e-6)), IsEmpty());
  EXPECT_THAT(io::needle_scale_warnings(cylinder(70e-6, 0.4)), ElementsAre(HasSubstr("400 um")));
  EXPECT_THAT(io::needle_scale_warnings(cylinder(70e-6, 10e-6)), ElementsAre(HasSubstr("is 10 um, outside the plausible 20 um to 5 mm")));
}

TEST(ScaleWarnings, ABodyMeshTallerThan3mOrSmallerThan1cm) {
  EXPECT_THAT(io::surface_scale_warnings(square(0.2, 4), "surface.unit"), IsEmpty());
  // A 250 mm head in mm declared as m: 250 m.
  EXPECT_THAT(io::surface_scale_warnings(square(250, 4), "surface.unit"),
              ElementsAre(AllOf(HasSubstr("largest extent (with surface.unit) is 250 m"), HasSubstr("250 mm"))));
  EXPECT_THAT(io::surface_scale_warnings(square(2e-3, 4), "--unit"), ElementsAre(HasSubstr("outside the plausible 10 mm to 3 m")));
}

TEST(ScaleWarnings, APatchSmallerThanTheBodyMeshsTypicalEdge) {
  patch::PatchDesignOptions options;
  options.width_u = options.width_v = 10e-3;
  options.needle = cylinder(70e-6, 400e-6);
  options.material = materials::material_preset("su-8");
  const patch::PatchDesign design = patch::patch_design(options);
  EXPECT_THAT(io::patch_scale_warnings(square(0.2, 40), design), IsEmpty());  // 5 mm edges
  EXPECT_THAT(io::patch_scale_warnings(square(0.2, 5), design),              // 40 mm edges
              ElementsAre(HasSubstr("patch.size 10 mm is smaller than the body surface's median edge 40 mm")));
}

insertion::IndentationCase punch_case(const std::string& needle) {
  return io::parse_indentation_case_toml("[needle]\n" + needle +
                                             "[tissue]\nwidth = \"1000 um\"\nlength = \"1000 um\"\n[[tissue.layers]]\n"
                                             "name = \"gel\"\nthickness = \"1000 um\"\nyoungs_modulus = \"0.2 MPa\"\n"
                                             "poisson_ratio = 0.45\n[loading]\ndepth = \"100 um\"\n",
                                         "case.toml");
}

TEST(ScaleWarnings, ANeedleLongerThanTheBlockIsHighOrWiderThanTheBlock) {
  EXPECT_THAT(io::indentation_scale_warnings(
                  punch_case("shape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"800 um\"\n")),
              IsEmpty());
  // A 5000 um needle on a 1000 um block.
  EXPECT_THAT(io::indentation_scale_warnings(
                  punch_case("shape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"5000 um\"\n")),
              ElementsAre(HasSubstr("the needle (5 mm long) is longer than the tissue block is high (1 mm)")));
  // A needle mesh in um declared as mm: 1000 times too large.
  insertion::IndentationCase c = punch_case("shape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"800 um\"\n");
  for (Eigen::Vector3d& v : c.needle.vertices) v *= 1000;
  c.geometry.reset();
  const std::vector<std::string> warnings = io::indentation_scale_warnings(c);
  EXPECT_THAT(warnings, testing::Contains(HasSubstr("the needle mesh's height (with needle.mesh_unit) is 800 mm")));
  EXPECT_THAT(warnings, testing::Contains(AllOf(HasSubstr("the needle is 230 mm across, wider than the 1 mm x 1 mm "
                                                          "tissue block"),
                                                HasSubstr("needle.mesh_unit"))));
}

// Deeper than the needle is long: under surface contact the needle's back end would enter the tissue (the §6.2 sharp
// bevel driven to its full 1000 um length stopped 4 um short with a negative force); the tip-node rule uses the tip
// face alone, so no warning there.
TEST(ScaleWarnings, AnIndentationDeeperThanTheNeedleIsLongUnderSurfaceContact) {
  const std::string needle = "shape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"80 um\"\n";
  insertion::IndentationCase c = punch_case(needle);
  c.solver.contact = fem::ContactModel::Surface;
  EXPECT_THAT(io::indentation_scale_warnings(c),
              ElementsAre(HasSubstr("loading.depth = 100 um is deeper than the needle is long (80 um)")));
  c.depth = 80e-6;
  EXPECT_THAT(io::indentation_scale_warnings(c), IsEmpty());
  c.depth = 100e-6;
  c.solver.contact = fem::ContactModel::TipNodes;
  EXPECT_THAT(io::indentation_scale_warnings(c), IsEmpty());
}

// An 800 um depth into a 500 um block cannot be simulated: refused, naming the key and the block's height.
TEST(ScaleWarnings, ADepthThroughTheBlockIsRefused) {
  EXPECT_THAT(
      [] {
        io::parse_indentation_case_toml(
            "[needle]\nshape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"1 mm\"\n[tissue]\n[[tissue.layers]]\n"
            "name = \"gel\"\nthickness = \"500 um\"\nyoungs_modulus = \"0.2 MPa\"\npoisson_ratio = 0.45\n[loading]\n"
            "depth = \"800 um\"\n",
            "case.toml");
      },
      testing::ThrowsMessage<InvalidInput>(
          HasSubstr("case.toml:12: key 'loading.depth': 800 um reaches through the 500 um high tissue block")));
}

}  // namespace
