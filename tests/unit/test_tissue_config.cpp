// [tissue] and [mesh] of a case file: units, "rest", presets and defaults; errors name FILE:LINE and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/tissue_config.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

mesh::LayeredBlockOptions parse(const std::string& text) { return io::parse_tissue_block_toml(text, "case.toml"); }

void expect_error(const std::string& text, const std::string& message) {
  EXPECT_THAT([&] { parse(text); }, testing::ThrowsMessage<InvalidInput>(HasSubstr(message))) << text;
}

constexpr const char* kLayers = R"([tissue]
width = "2 mm"
length = "1500 um"
[[tissue.layers]]
name = "stratum corneum"
thickness = "20 um"
youngs_modulus = "1 GPa"
[[tissue.layers]]
name = "dermis"
thickness = "rest"
youngs_modulus = "0.08 MPa"
poisson_ratio = 0.45
[mesh]
size_at_tip = "15 um"
size_far = "0.2 mm"
sites = [["-500 um", "0 um"], ["0.5 mm", "100 um"]]
site_circle_radius = "115 um"
split = true
[needle]
anything = "is ignored here"
)";

}  // namespace

TEST(TissueConfig, LayersWithUnitsAndRest) {
  const mesh::LayeredBlockOptions o = parse(kLayers);
  EXPECT_DOUBLE_EQ(o.width, 2e-3);
  EXPECT_DOUBLE_EQ(o.length, 1500e-6);
  ASSERT_EQ(o.layers.size(), 2u);
  EXPECT_EQ(o.layers[0].name, "stratum corneum");
  EXPECT_DOUBLE_EQ(o.layers[0].youngs_modulus, 1e9);
  EXPECT_DOUBLE_EQ(o.layers[0].poisson_ratio, 0.4);  // default
  EXPECT_NEAR(o.layers[1].thickness, 1150e-6 - 20e-6, 1e-18);  // "rest" of the default 1150 um
  EXPECT_DOUBLE_EQ(o.layers[1].poisson_ratio, 0.45);
  EXPECT_DOUBLE_EQ(o.size_at_site, 15e-6);
  EXPECT_DOUBLE_EQ(o.size_far, 200e-6);
  ASSERT_EQ(o.insertion_sites.size(), 2u);
  EXPECT_DOUBLE_EQ(o.insertion_sites[1].x(), 500e-6);
  EXPECT_DOUBLE_EQ(o.insertion_sites[1].y(), 100e-6);
  EXPECT_DOUBLE_EQ(o.site_circle_radius, 115e-6);
  EXPECT_TRUE(o.split);
}

// An empty case file is an error naming what is missing (it used to mesh the default block without a word).
TEST(TissueConfig, AnEmptyCaseNamesTheMissingTissueTable) {
  EXPECT_THAT([] { parse(""); }, testing::ThrowsMessage<InvalidInput>(HasSubstr("case.toml:1: missing table [tissue]")));
  EXPECT_THAT([] { parse("[mesh]\nsize_at_tip = \"40 um\"\n"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("expected a table [tissue] with preset = ")));
}

TEST(TissueConfig, DefaultsAndPresets) {
  const mesh::LayeredBlockOptions o = parse("[tissue]\n");
  EXPECT_FALSE(o.split);
  ASSERT_EQ(o.layers.size(), 3u);
  EXPECT_DOUBLE_EQ(o.layers[1].youngs_modulus, 0.134e6);
  EXPECT_DOUBLE_EQ(o.width, 3000e-6);
  const mesh::LayeredBlockOptions phantom = parse("[tissue]\npreset = \"silicone-0.2mpa\"\nheight = \"2 mm\"\n");
  ASSERT_EQ(phantom.layers.size(), 1u);
  EXPECT_DOUBLE_EQ(phantom.layers[0].thickness, 2e-3);
  EXPECT_DOUBLE_EQ(phantom.layers[0].poisson_ratio, 0.49);
  const mesh::LayeredBlockOptions tall = parse("[tissue]\nheight = \"2000 um\"\n");
  EXPECT_NEAR(tall.layers[2].thickness, 1840e-6, 1e-18);
}

TEST(TissueConfig, ErrorsNameLineAndKey) {
  expect_error("[tissue]\nwidth = 3000\n", "case.toml:2: key 'tissue.width': 3000 is a bare number without a unit");
  expect_error("[tissue]\nwidht = \"1 mm\"\n", "case.toml:2: unknown key 'tissue.widht'");
  expect_error("[[tissue.layers]]\nname = \"a\"\nthickness = \"0 um\"\nyoungs_modulus = \"1 MPa\"\n",
               "case.toml:3: key 'tissue.layers[0].thickness': '0 um' is not positive");
  expect_error("[[tissue.layers]]\nname = \"a\"\nthickness = \"-5 um\"\nyoungs_modulus = \"1 MPa\"\n",
               "key 'tissue.layers[0].thickness': '-5 um' is not positive");
  expect_error("[[tissue.layers]]\nname = \"a\"\nthickness = \"rest\"\nyoungs_modulus = \"1 MPa\"\n"
               "[[tissue.layers]]\nname = \"b\"\nthickness = \"5 um\"\nyoungs_modulus = \"1 MPa\"\n",
               "case.toml:3: key 'tissue.layers[0].thickness': \"rest\" is allowed only for the last layer");
  expect_error("[tissue]\nheight = \"100 um\"\n[[tissue.layers]]\nname = \"a\"\nthickness = \"200 um\"\n"
               "youngs_modulus = \"1 MPa\"\n[[tissue.layers]]\nname = \"b\"\nthickness = \"rest\"\n"
               "youngs_modulus = \"1 MPa\"\n",
               "key 'tissue.layers[1].thickness': \"rest\" of a 100 um block below 200 um of layers is not positive");
  expect_error("[[tissue.layers]]\nname = \"a\"\nthickness = \"5 um\"\nyoungs_modulus = \"1 MPa\"\npoisson_ratio = 0.5\n",
               "case.toml:5: key 'tissue.layers[0].poisson_ratio': 0.5 is out of range, expected a number in (-1, 0.5)");
  expect_error("[tissue]\npreset = \"liver\"\n", "case.toml:2: key 'tissue.preset': unknown tissue preset 'liver'");
  expect_error("[tissue]\n[mesh]\nsize_at_tip = \"50 um\"\nsize_far = \"20 um\"\n",
               "case.toml:4: key 'mesh.size_far': 20 um is smaller than size_at_tip = 50 um");
  expect_error("[tissue]\n[mesh]\nsites = [[\"2000 um\", \"0 um\"]]\n",
               "key 'mesh.sites[0]': (2000, 0) um is not inside the 3000 x 3000 um top surface");
  expect_error("[tissue]\nheight = \"1 mm\"\n[[tissue.layers]]\nname = \"a\"\nthickness = \"5 um\"\n"
               "youngs_modulus = \"1 MPa\"\n",
               "case.toml:2: key 'tissue.height': 1000 um differs from the 5 um sum of the layer thicknesses");
}

TEST(TissueConfig, UserMshFileWithNamedLayers) {
  const auto dir = std::filesystem::temp_directory_path() / ("needlekit-tissue-msh-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // Two tetrahedra, top surface z = 0, in physical volumes "sc" (above) and "dermis" (below), coordinates in um.
  std::ofstream(dir / "user.msh")
      << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3 1 \"sc\"\n3 2 \"dermis\"\n$EndPhysicalNames\n"
         "$Nodes\n5\n1 0 0 0\n2 100 0 0\n3 0 100 0\n4 0 0 -100\n5 100 100 -200\n$EndNodes\n"
         "$Elements\n2\n1 4 2 1 1 1 3 2 4\n2 4 2 2 2 3 2 4 5\n$EndElements\n";
  const std::string layers = "[[tissue.layers]]\nname = \"sc\"\nthickness = \"20 um\"\nyoungs_modulus = \"100 MPa\"\n"
                             "[[tissue.layers]]\nname = \"dermis\"\nthickness = \"rest\"\nyoungs_modulus = \"0.08 MPa\"\n";
  std::ofstream(dir / "case.toml") << layers << "[mesh]\nfile = \"user.msh\"\nunit = \"um\"\n";
  const io::TissueCase tissue = io::read_tissue_case(dir / "case.toml");
  EXPECT_EQ(tissue.msh_file, dir / "user.msh");
  const mesh::LayeredBlockResult r = io::tissue_mesh(tissue);
  ASSERT_EQ(r.mesh.tets.size(), 2u);
  EXPECT_EQ(r.mesh.tet_layer, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(r.mesh.layers[1].youngs_modulus, 0.08e6);
  EXPECT_DOUBLE_EQ(r.mesh.nodes[4].z(), -200e-6);
  EXPECT_THAT([&] { io::read_tissue_block(dir / "case.toml"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("names a mesh file, expected a parametric block")));

  // In mm the top is still z = 0 but the layers are missing; shifted up, the top is not z = 0.
  std::ofstream(dir / "case.toml") << "[tissue]\n[mesh]\nfile = \"user.msh\"\nunit = \"mm\"\n";
  EXPECT_THAT([&] { io::tissue_mesh(io::read_tissue_case(dir / "case.toml")); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("no physical volume group named \"stratum corneum\"")));
  std::ofstream(dir / "up.msh")
      << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 10\n2 100 0 10\n3 0 100 10\n4 0 0 -90\n$EndNodes\n"
         "$Elements\n1\n1 4 2 1 1 1 3 2 4\n$EndElements\n";
  std::ofstream(dir / "case.toml") << "[tissue]\npreset = \"silicone-0.2mpa\"\n[mesh]\nfile = \"up.msh\"\n";
  EXPECT_THAT([&] { io::tissue_mesh(io::read_tissue_case(dir / "case.toml")); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("up.msh: the mesh's top is at z = 10 um; expected")));
  std::ofstream(dir / "case.toml") << "[tissue]\n[mesh]\nfile = \"up.msh\"\nsize_far = \"100 um\"\n";
  EXPECT_THAT([&] { io::read_tissue_case(dir / "case.toml"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("case.toml:4: key 'mesh.size_far': given together with file")));
  std::filesystem::remove_all(dir);
}
