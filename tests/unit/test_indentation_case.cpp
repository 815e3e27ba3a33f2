// Indentation case files: a full case parses to SI values, presets and "rest" layers fill the block, several needles
// are placed tip-down, and every bad input is an InvalidInput naming FILE:LINE and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/fem/parallel_session.hpp"
#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/mesh/tet_count_estimate.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "needlekit/needle/rounded_edges.hpp"
#include "../support/test_text.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

// Line numbers matter: the error cases below name them.
constexpr std::string_view kCase = R"(name = "punch"
[needle]
shape = "cylinder"
tip_diameter = "230 um"
length = "1000 um"

[tissue]
width = "3000 um"
length = "3000 um"
[[tissue.layers]]
name = "stratum corneum"
thickness = "20 um"
youngs_modulus = "100 MPa"
poisson_ratio = 0.4
[[tissue.layers]]
name = "rest"
thickness = "rest"
youngs_modulus = "0.08 MPa"
poisson_ratio = 0.4

[mesh]
size_at_tip = "20 um"
size_far = "250 um"

[loading]
depth = "200 um"
steps = 20

[model]
law = "svk"
contact = "tip-nodes"
element = "quadratic"

[puncture]
critical_pressure = "0.663 MPa"
toughness = "100 J/m2"
)";

using test::replaced;

insertion::IndentationCase parse(std::string_view text) { return io::parse_indentation_case_toml(text, "case.toml"); }

// The message of the InvalidInput that parsing `text` throws.
std::string error_of(std::string_view text) {
  try {
    parse(text);
  } catch (const InvalidInput& error) {
    return error.what();
  } catch (const IoError& error) {
    return std::string("IoError: ") + error.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

TEST(IndentationCase, ParsesEverySection) {
  const insertion::IndentationCase c = parse(kCase);
  EXPECT_EQ(c.name, "punch");
  ASSERT_TRUE(c.geometry.has_value());
  EXPECT_DOUBLE_EQ(c.geometry->tip_diameter, 230e-6);
  EXPECT_DOUBLE_EQ(c.geometry->base_diameter, 230e-6);
  EXPECT_FALSE(c.needle.triangles.empty());
  ASSERT_EQ(c.needles.size(), 1u);
  EXPECT_DOUBLE_EQ(c.needles[0].tip_height, 0.0);
  ASSERT_EQ(c.block.layers.size(), 2u);
  EXPECT_DOUBLE_EQ(c.block.layers[0].thickness, 20e-6);
  EXPECT_NEAR(c.block.layers[1].thickness, 1130e-6, 1e-15);  // "rest" of the default 1150 um block
  EXPECT_DOUBLE_EQ(c.block.layers[1].youngs_modulus, 0.08e6);
  EXPECT_DOUBLE_EQ(c.block.size_at_site, 20e-6);
  EXPECT_DOUBLE_EQ(c.depth, 200e-6);
  EXPECT_EQ(c.steps, 20);
  EXPECT_EQ(c.solver.law, fem::MaterialLaw::StVenantKirchhoff);
  EXPECT_EQ(c.solver.contact, fem::ContactModel::TipNodes);
  EXPECT_EQ(c.solver.order, fem::ElementOrder::Quadratic);
  EXPECT_DOUBLE_EQ(*c.puncture.critical_pressure, 0.663e6);
  EXPECT_DOUBLE_EQ(*c.puncture.toughness, 100.0);
  EXPECT_TRUE(c.stop_at_puncture);
}

TEST(IndentationCase, SolverSection) {
  const fem::SolverOptions defaults;
  EXPECT_EQ(parse(kCase).solver.residual_tolerance, defaults.residual_tolerance);  // no [solver]: the defaults
  // kCase with a [solver] section of these lines (it starts on line 35).
  const auto with_solver = [](std::string_view lines) {
    return replaced(kCase, "[puncture]", "[solver]\n" + std::string(lines) + "[puncture]");
  };
  const std::string all = with_solver("residual_tolerance = 1e-8\ndisplacement_tolerance = 1e-7\n"
                                      "energy_tolerance = 1e-12\npenetration_tolerance = 0.01\nmax_iterations = 40\n"
                                      "max_cutbacks = 3\npredictor = \"linearised\"\nlinear_solver = \"cholesky\"\n"
                                      "penalty_factor = 10\nthreads = 1\n");
  // The surface contact's settings do not apply to tip-node contact: an error, not silently ignored.
  EXPECT_THAT(error_of(all), HasSubstr("key 'solver.penalty_factor': applies only to [model] contact = "
                                       "\"surface\", but contact = \"tip-nodes\""));
  const auto c = parse(replaced(all, "contact = \"tip-nodes\"", "contact = \"surface\""));
  EXPECT_DOUBLE_EQ(c.solver.residual_tolerance, 1e-8);
  EXPECT_DOUBLE_EQ(c.solver.displacement_tolerance, 1e-7);
  EXPECT_DOUBLE_EQ(c.solver.energy_tolerance, 1e-12);
  EXPECT_DOUBLE_EQ(c.solver.penetration_tolerance, 0.01);
  EXPECT_EQ(c.solver.max_iterations, 40);
  EXPECT_EQ(c.solver.max_cutbacks, 3);
  EXPECT_FALSE(c.solver.extrapolate_predictor);
  EXPECT_EQ(c.solver.linear_solver, fem::LinearSolver::Cholesky);
  EXPECT_DOUBLE_EQ(c.solver.penalty_factor, 10.0);
  EXPECT_EQ(c.solver.threads, 1);
  // Friction and the second pass of surface contact (docs/fem_solver.md): read, defaults 0 and off, a negative
  // coefficient an error naming the key.
  EXPECT_EQ(c.solver.friction, 0.0);
  EXPECT_FALSE(c.solver.two_pass);
  const auto surface = [&](std::string_view lines) {
    return replaced(with_solver(lines), "contact = \"tip-nodes\"", "contact = \"surface\"");
  };
  const auto rough = parse(surface("friction = 0.3\ntwo_pass = true\n"));
  EXPECT_DOUBLE_EQ(rough.solver.friction, 0.3);
  EXPECT_TRUE(rough.solver.two_pass);
  EXPECT_THAT(error_of(surface("friction = -0.1\n")),
              HasSubstr("case.toml:35: key 'solver.friction': -0.1 is out of range, expected a number >= 0"));
  // Rezoning: read under surface contact with linear tetrahedra; its settings without rezone = true are an error.
  const auto linear_surface = [&](std::string_view lines) {
    return replaced(replaced(surface(lines), "element = \"quadratic\"", "element = \"linear\""), "law = \"svk\"", "law = \"neo-hookean\"");
  };
  const auto rezoned = parse(linear_surface("rezone = true\nrezone_volume_ratio = 0.4\nmax_remeshes = 3\n"));
  EXPECT_TRUE(rezoned.solver.rezone);
  EXPECT_DOUBLE_EQ(rezoned.solver.rezone_volume_ratio, 0.4);
  EXPECT_EQ(rezoned.solver.max_remeshes, 3);
  EXPECT_THAT(error_of(linear_surface("max_remeshes = 3\n")),
              HasSubstr("key 'solver.max_remeshes': applies only with rezone = true"));
  EXPECT_THAT(error_of(linear_surface("rezone = true\nrezone_volume_ratio = 1.5\n")),
              HasSubstr("key 'solver.rezone_volume_ratio': 1.5 is out of range, expected a number in (0, 1)"));
  EXPECT_THAT(error_of(surface("rezone = true\n")),  // kCase's quadratic tetrahedra
              HasSubstr("solver rezone = true meshes the deformed tissue anew under surface contact with linear"));
  EXPECT_THAT(error_of(with_solver("friction = 0.3\n")),
              HasSubstr("key 'solver.friction': applies only to [model] contact = \"surface\""));
  EXPECT_THAT(error_of(with_solver("residual_tolerance = 1.5\n")),
              HasSubstr("case.toml:35: key 'solver.residual_tolerance': 1.5 is out of range, expected a number in (0, 1)"));
  EXPECT_THAT(error_of(with_solver("volumetric = \"mixed\"\n")),
              HasSubstr("key 'solver.volumetric': unknown value 'mixed', expected one of: \"auto\" | \"element\" | \"nodal-average\""));
  // An option that does not apply to the chosen model (kCase: St Venant-Kirchhoff, quadratic) is an error before anything runs.
  EXPECT_THAT(error_of(with_solver("volumetric = \"nodal-average\"\n")),
              HasSubstr("solver volumetric = \"nodal-average\" averages the neo-Hookean law's volumetric term"));
  EXPECT_EQ(parse(with_solver("volumetric = \"element\"\n")).solver.volumetric, fem::VolumetricFormulation::Element);
  EXPECT_THAT(error_of(with_solver("predictor = \"cubic\"\n")),
              HasSubstr("key 'solver.predictor': unknown value 'cubic', expected one of: \"secant\" | \"linearised\""));
  EXPECT_THAT(error_of(with_solver("max_iterations = -1\n")),
              HasSubstr("key 'solver.max_iterations': -1 is out of range"));
  EXPECT_EQ(parse(with_solver("linear_solver = \"two-grid\"\n")).solver.linear_solver, fem::LinearSolver::TwoGrid);
  EXPECT_EQ(parse(with_solver("linear_solver = \"auto\"\n")).solver.linear_solver, fem::LinearSolver::Automatic);
  EXPECT_THAT(error_of(with_solver("linear_solver = \"lu\"\n")),
              HasSubstr("expected one of: \"auto\" | \"two-grid\" | \"cholesky-cg\" | \"cholesky\""));
  EXPECT_THAT(error_of(with_solver("tolerance = 1e-6\n")),
              HasSubstr("unknown key 'solver.tolerance'"));
}

// [solver] backend: "builtin" always; "petsc" only in a build with the PETSc backend, else an error naming the key.
TEST(IndentationCase, SolverBackend) {
  const std::string with_backend = std::string(kCase) + "\n[solver]\nbackend = \"petsc\"\n";
  if (fem::backend_compiled(fem::SolverBackend::Petsc)) {
    EXPECT_EQ(parse(with_backend).solver.backend, fem::SolverBackend::Petsc);
  } else {
    EXPECT_THAT(error_of(with_backend),
                HasSubstr("key 'solver.backend': \"petsc\" is not in this build, expected builtin"));
  }
  EXPECT_EQ(parse(std::string(kCase) + "\n[solver]\nbackend = \"builtin\"\n").solver.backend,
            fem::SolverBackend::Builtin);
  EXPECT_THAT(error_of(std::string(kCase) + "\n[solver]\nbackend = \"mpi\"\n"),
              HasSubstr("expected one of: \"builtin\" | \"petsc\""));
}

// [solver] volumetric_stabilization applies to the nodal-averaged volume only: an error wherever it cannot act.
TEST(IndentationCase, VolumetricStabilization) {
  const std::string neo_hookean_linear =
      replaced(replaced(kCase, "law = \"svk\"", "law = \"neo-hookean\""), "element = \"quadratic\"", "element = \"linear\"");
  const auto with = [&](std::string_view base, std::string_view lines) {
    return replaced(base, "[puncture]", "[solver]\n" + std::string(lines) + "[puncture]");
  };
  const std::string incompressible = replaced(neo_hookean_linear, "poisson_ratio = 0.4", "poisson_ratio = 0.49");
  EXPECT_DOUBLE_EQ(parse(incompressible).solver.volumetric_stabilization, fem::SolverOptions{}.volumetric_stabilization);
  EXPECT_DOUBLE_EQ(parse(with(incompressible, "volumetric_stabilization = 1.5\n")).solver.volumetric_stabilization, 1.5);
  EXPECT_DOUBLE_EQ(
      parse(with(neo_hookean_linear, "volumetric = \"nodal-average\"\nvolumetric_stabilization = 0\n")).solver.volumetric_stabilization,
      0.0);
  EXPECT_THAT(error_of(with(incompressible, "volumetric_stabilization = -1\n")),
              HasSubstr("key 'solver.volumetric_stabilization': -1 is out of range, expected a number >= 0"));
  EXPECT_THAT(error_of(with(neo_hookean_linear, "volumetric_stabilization = 1\n")),
              HasSubstr("key 'solver.volumetric_stabilization': applies only to the nodal-averaged volume, which "
                        "volumetric = \"auto\" gives layers with poisson_ratio >= 0.45 and no layer has one"));
  EXPECT_THAT(error_of(with(incompressible, "volumetric = \"element\"\nvolumetric_stabilization = 1\n")),
              HasSubstr("key 'solver.volumetric_stabilization': applies only to the nodal-averaged volume"));
  EXPECT_THAT(error_of(with(kCase, "volumetric_stabilization = 1\n")),
              HasSubstr("key 'solver.volumetric_stabilization': applies only to the nodal-averaged volume"));
}

TEST(IndentationCase, WhichBlocksAreMeshedWithACoarseLevel) {
  // kCase with linear elements: "auto" meshes a coarse level (and so takes the two-grid solver) from
  // kTwoGridMinimumTetrahedra estimated tetrahedra on; "two-grid" always; never with a mesh file.
  const std::string linear = replaced(replaced(kCase, "element = \"quadratic\"", "element = \"linear\""),
                                      "law = \"svk\"", "law = \"neo-hookean\"");
  const auto sized = [&](std::string_view size_at_tip) {
    return replaced(linear, "size_at_tip = \"20 um\"", "size_at_tip = \"" + std::string(size_at_tip) + "\"");
  };
  insertion::IndentationCase small = parse(replaced(sized("40 um"), "width = \"3000 um\"\nlength = \"3000 um\"",
                                                    "width = \"1000 um\"\nlength = \"1000 um\"")),
                             large = parse(sized("12 um"));
  EXPECT_LT(mesh::estimated_tetrahedra(small.block), insertion::kTwoGridMinimumTetrahedra);
  EXPECT_GE(mesh::estimated_tetrahedra(large.block), insertion::kTwoGridMinimumTetrahedra);
  EXPECT_FALSE(insertion::meshes_coarse_level(small));
  EXPECT_TRUE(insertion::meshes_coarse_level(large));
  small.solver.linear_solver = fem::LinearSolver::TwoGrid;
  EXPECT_TRUE(insertion::meshes_coarse_level(small));
  large.solver.linear_solver = fem::LinearSolver::CholeskyCg;
  EXPECT_FALSE(insertion::meshes_coarse_level(large));
  // The same threshold with a nodal average (ν >= 0.45).
  const auto nearly_incompressible = [&](const std::string& text) {
    return parse(replaced(text, "poisson_ratio = 0.4\n[[tissue", "poisson_ratio = 0.49\n[[tissue"));
  };
  const insertion::IndentationCase medium = nearly_incompressible(sized("80 um")),
                                   coarse = nearly_incompressible(
                                       replaced(sized("40 um"), "width = \"3000 um\"\nlength = \"3000 um\"",
                                                "width = \"1000 um\"\nlength = \"1000 um\""));
  EXPECT_TRUE(uses_nodal_average(medium) && uses_nodal_average(coarse));
  EXPECT_GE(mesh::estimated_tetrahedra(medium.block), insertion::kTwoGridMinimumTetrahedra);
  EXPECT_LT(mesh::estimated_tetrahedra(coarse.block), insertion::kTwoGridMinimumTetrahedra);
  EXPECT_TRUE(insertion::meshes_coarse_level(medium));
  EXPECT_FALSE(insertion::meshes_coarse_level(coarse));
  EXPECT_FALSE(insertion::meshes_coarse_level(parse(replaced(sized("12 um"), "element = \"linear\"",
                                                             "element = \"quadratic\""))));
}

TEST(IndentationCase, PresetsHeightsAndArrays) {
  // The skin preset in a taller block, and two needles.
  const std::string text = R"([needle]
shape = "cone"
tip_diameter = "30 um"
base_diameter = "230 um"
length = "1000 um"
[[needles]]
x = "-800 um"
y = "-800 um"
[[needles]]
x = "800 um"
y = "-800 um"
tip_height = "10 um"
[tissue]
preset = "skin"
height = "2000 um"
[loading]
depth = "200 um"
)";
  const insertion::IndentationCase c = parse(text);
  EXPECT_EQ(c.name, "case");
  ASSERT_EQ(c.block.layers.size(), 3u);
  double total = 0;
  for (const auto& layer : c.block.layers) total += layer.thickness;
  EXPECT_NEAR(total, 2000e-6, 1e-12);
  EXPECT_DOUBLE_EQ(c.block.layers[0].thickness, 20e-6);
  ASSERT_EQ(c.needles.size(), 2u);
  EXPECT_DOUBLE_EQ(c.needles[1].position.x(), 800e-6);
  EXPECT_DOUBLE_EQ(c.needles[1].tip_height, 10e-6);
  // Defaults: neo-Hookean, surface contact, linear elements.
  EXPECT_EQ(c.solver.law, fem::MaterialLaw::NeoHookean);
  EXPECT_EQ(c.solver.contact, fem::ContactModel::Surface);

  // Placed tip-down: the lowest point of each needle is its tip, at the tip height, above the site. With surface
  // contact the solver gets the eroded core and the edge radius: the core's lowest vertex is that radius higher.
  const auto indenters = insertion::placed_indenters(c);
  ASSERT_EQ(indenters.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    double lowest = 1, highest = -1;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& v : indenters[i].surface.vertices) {
      lowest = std::min(lowest, v.z());
      highest = std::max(highest, v.z());
      centre += v.head<2>();
    }
    centre /= static_cast<double>(indenters[i].surface.vertices.size());
    const double rho = indenters[i].edge_radius;
    EXPECT_DOUBLE_EQ(rho, insertion::effective_edge_radius(c));
    EXPECT_NEAR(lowest - rho, c.needles[i].tip_height, 1e-15);
    EXPECT_NEAR(highest, c.needles[i].tip_height + 1000e-6, 1e-12);
    EXPECT_NEAR((centre - c.needles[i].position).norm(), 0, 1e-6);
    EXPECT_GT(geometry::signed_volume(indenters[i].surface), 0);  // still outward-oriented
  }
}

TEST(IndentationCase, NeedleFromStl) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "needlekit-case-stl";
  std::filesystem::create_directories(dir);
  const needle::NeedleGeometry cone{needle::Shape::Cone, 30e-6, 230e-6, 0, 1000e-6};
  geometry::write_stl(needle::needle_surface_mesh(cone), dir / "cone.stl", 1e6);  // in um
  const std::string text = replaced(kCase, "shape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"1000 um\"",
                                    "mesh = \"cone.stl\"\nmesh_unit = \"um\"");
  std::ofstream(dir / "case.toml") << text;
  const insertion::IndentationCase c = io::read_indentation_case(dir / "case.toml");
  EXPECT_FALSE(c.geometry.has_value());
  EXPECT_NEAR(geometry::signed_volume(c.needle), needle::volume(cone), 2e-3 * needle::volume(cone));
  // A mesh's edges are the mesh's: an edge radius is bad input there.
  std::ofstream(dir / "rounded.toml") << replaced(text, "mesh_unit = \"um\"", "mesh_unit = \"um\"\nedge_radius = \"2 um\"");
  EXPECT_THAT([&] { io::read_indentation_case(dir / "rounded.toml"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("key 'needle.edge_radius': given for a needle given as a mesh")));
  std::filesystem::remove_all(dir);
}

TEST(IndentationCase, EdgeRadius) {
  // Surface contact on a parametric needle: the given radius, or the default; tip nodes: none (a flat face).
  const std::string surface = replaced(kCase, "contact = \"tip-nodes\"", "contact = \"surface\"");
  const auto with_radius = [](std::string_view text, const std::string& radius) {
    return replaced(text, "length = \"1000 um\"", "length = \"1000 um\"\nedge_radius = \"" + radius + "\"");
  };
  const insertion::IndentationCase given = parse(with_radius(surface, "5 um"));
  ASSERT_TRUE(given.edge_radius.has_value());
  EXPECT_DOUBLE_EQ(*given.edge_radius, 5e-6);
  EXPECT_DOUBLE_EQ(insertion::effective_edge_radius(given), 5e-6);
  EXPECT_DOUBLE_EQ(insertion::effective_edge_radius(parse(surface)), needle::kTypicalEdgeRadius);
  EXPECT_EQ(insertion::effective_edge_radius(parse(kCase)), 0.0);
  // Bad input: not less than the tip's radius, with tip-nodes contact, negative.
  EXPECT_THAT(error_of(with_radius(surface, "120 um")),
              HasSubstr("key 'needle.edge_radius': 120 um, expected at least 0 and less than 115 um (the tip's radius)"));
  EXPECT_THAT(error_of(with_radius(kCase, "5 um")), HasSubstr("key 'needle.edge_radius': given with contact = \"tip-nodes\""));
  EXPECT_THAT(error_of(with_radius(surface, "-1 um")), HasSubstr("case.toml:6: key 'needle.edge_radius': '-1 um' is negative"));
}

TEST(IndentationCase, AveragedPressureCriterion) {
  const std::string surface = replaced(kCase, "contact = \"tip-nodes\"", "contact = \"surface\"");
  const std::string averaged = replaced(surface, "toughness = \"100 J/m2\"",
                                        "criterion = \"averaged-pressure\"\nmaterial_length = \"40 um\"");
  const insertion::IndentationCase c = parse(averaged);
  EXPECT_EQ(c.puncture.criterion, insertion::PunctureLaw::AveragedPressure);
  EXPECT_DOUBLE_EQ(c.puncture.material_length, 40e-6);
  EXPECT_DOUBLE_EQ(*c.puncture.critical_pressure, 0.663e6);
  EXPECT_EQ(parse(kCase).puncture.criterion, insertion::PunctureLaw::Dissertation);  // the default
  EXPECT_DOUBLE_EQ(parse(kCase).puncture.material_length, 50e-6);
  // Bad input, at the file's line and key: a length without a unit, a negative one, an unknown law, the law under
  // the tip-node rule (no contact field), with a toughness, or without its critical pressure.
  EXPECT_THAT(error_of(replaced(averaged, "material_length = \"40 um\"", "material_length = 40")),
              HasSubstr("case.toml:37: key 'puncture.material_length': 40 is a bare number"));
  EXPECT_THAT(error_of(replaced(averaged, "material_length = \"40 um\"", "material_length = \"-40 um\"")),
              HasSubstr("case.toml:37: key 'puncture.material_length': '-40 um' is not positive, expected a positive length"));
  EXPECT_THAT(error_of(replaced(averaged, "averaged-pressure", "energy")),
              HasSubstr("case.toml:36: key 'puncture.criterion': unknown value 'energy', expected one of: "
                        "\"dissertation\" | \"averaged-pressure\""));
  EXPECT_THAT(error_of(replaced(averaged, "contact = \"surface\"", "contact = \"tip-nodes\"")),
              HasSubstr("case.toml:36: key 'puncture.criterion': \"averaged-pressure\" with contact = \"tip-nodes\""));
  EXPECT_THAT(error_of(averaged + "toughness = \"10 J/m2\"\n"),
              HasSubstr("case.toml:38: key 'puncture.toughness': given with criterion = \"averaged-pressure\""));
  EXPECT_THAT(error_of(replaced(averaged, "critical_pressure = \"0.663 MPa\"\n", "")),
              HasSubstr("key 'puncture.criterion': \"averaged-pressure\" without a critical_pressure"));
  EXPECT_THAT(error_of(replaced(surface, "toughness = \"100 J/m2\"", "toughness = 10")),
              HasSubstr("key 'puncture.toughness': 10 is a bare number"));
}

TEST(IndentationCase, ErrorsNameFileLineAndKey) {
  // Zero and negative layer thickness.
  EXPECT_THAT(error_of(replaced(kCase, "thickness = \"20 um\"", "thickness = \"0 um\"")),
              HasSubstr("case.toml:12: key 'tissue.layers[0].thickness': '0 um' is not positive"));
  EXPECT_THAT(error_of(replaced(kCase, "thickness = \"20 um\"", "thickness = \"-5 um\"")),
              HasSubstr("case.toml:12: key 'tissue.layers[0].thickness'"));
  // nu >= 0.5.
  EXPECT_THAT(error_of(replaced(kCase, "poisson_ratio = 0.4", "poisson_ratio = 0.5")),
              HasSubstr("case.toml:14: key 'tissue.layers[0].poisson_ratio': 0.5 is out of range"));
  // A needle that starts inside the tissue.
  EXPECT_THAT(error_of(replaced(kCase, "length = \"1000 um\"", "length = \"1000 um\"\ntip_height = \"-10 um\"")),
              HasSubstr("case.toml:6: key 'needle.tip_height': '-10 um' is negative: the needle would start inside "
                        "the tissue"));
  // Unknown law and contact.
  EXPECT_THAT(error_of(replaced(kCase, "law = \"svk\"", "law = \"mooney\"")),
              HasSubstr("case.toml:30: key 'model.law': unknown value 'mooney', expected one of: \"neo-hookean\" | \"svk\""));
  EXPECT_THAT(error_of(replaced(kCase, "contact = \"tip-nodes\"", "contact = \"node\"")),
              HasSubstr("case.toml:31: key 'model.contact': unknown value 'node'"));
  // Bare numbers for dimensional values.
  EXPECT_THAT(error_of(replaced(kCase, "depth = \"200 um\"", "depth = 200")),
              HasSubstr("case.toml:26: key 'loading.depth': 200 is a bare number without a unit"));
  EXPECT_THAT(error_of(replaced(kCase, "youngs_modulus = \"100 MPa\"", "youngs_modulus = 100e6")),
              HasSubstr("case.toml:13: key 'tissue.layers[0].youngs_modulus': 100000000 is a bare number"));
  EXPECT_THAT(error_of(replaced(kCase, "critical_pressure = \"0.663 MPa\"", "critical_pressure = 0.663")),
              HasSubstr("key 'puncture.critical_pressure': 0.663 is a bare number"));
  // "rest" not last; unknown key; missing depth; a needle outside the block; steps < 1.
  EXPECT_THAT(error_of(replaced(kCase, "thickness = \"20 um\"", "thickness = \"rest\"")),
              HasSubstr("key 'tissue.layers[0].thickness': \"rest\" is allowed only for the last layer"));
  EXPECT_THAT(error_of(replaced(kCase, "steps = 20", "stepz = 20")), HasSubstr("unknown key 'loading.stepz'"));
  EXPECT_THAT(error_of(replaced(kCase, "depth = \"200 um\"\n", "")), HasSubstr("key 'loading.depth': missing"));
  EXPECT_THAT(error_of(replaced(kCase, "[tissue]", "[[needles]]\nx = \"2000 um\"\n[tissue]")),
              HasSubstr("key 'needles[0]': (2000 um, 0 um) is outside the 3000 um x 3000 um block"));
  EXPECT_THAT(error_of(replaced(kCase, "steps = 20", "steps = 0")),
              HasSubstr("key 'loading.steps': 0 is out of range, expected an integer in [1, 10000]"));
  // A cylinder out of proportion whose base_diameter is left out (it is the tip's): the message names tip_diameter
  // (fuzzing found the reader naming the missing key through a null node).
  EXPECT_THAT(error_of(replaced(kCase, "tip_diameter = \"230 um\"\nlength = \"1000 um\"",
                                "tip_diameter = \"2301111111 um\"\nlength = \"100 um\"")),
              HasSubstr("case.toml:4: key 'needle.tip_diameter': 2.30111e+09 um is more than 1e+06 times"));
  // The work limits (core/limits.hpp): a typo cannot ask for days of load steps or a needle mesh of 1e9 quads.
  EXPECT_THAT(error_of(replaced(kCase, "steps = 20", "steps = 200000")),
              HasSubstr("key 'loading.steps': 200000 is out of range, expected an integer in [1, 10000] (the upper end "
                        "is needlekit's work limit)"));
  EXPECT_THAT(error_of(replaced(kCase, "size_far = \"250 um\"", "size_far = \"10 um\"")),
              HasSubstr("key 'mesh.size_far': 10 um is smaller than size_at_tip = 20 um"));
  const std::string preset_case = std::string(kCase.substr(0, kCase.find("[[tissue.layers]]"))) + "preset = \"liver\"\n[loading]\n"
                                  "depth = \"200 um\"\n";
  EXPECT_THAT(error_of(preset_case), HasSubstr("case.toml:10: key 'tissue.preset': unknown tissue preset 'liver'"));
}

}  // namespace

namespace {

TEST(IndentationCase, EveryIndentExampleParses) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "examples")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("indent_", 0) != 0) continue;
    SCOPED_TRACE(name);
    const insertion::IndentationCase c = io::read_indentation_case(entry.path());
    EXPECT_GT(c.depth, 0);
    EXPECT_FALSE(c.block.layers.empty());
    ++count;
  }
  EXPECT_GE(count, 7);
  const insertion::IndentationCase four =
      io::read_indentation_case(std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "examples/indent_fig_6_3_four_needles.toml");
  ASSERT_EQ(four.needles.size(), 4u);
  EXPECT_NEAR((four.needles[1].position - four.needles[0].position).norm(), 1600e-6, 1e-12);  // Fig 6.3
  EXPECT_DOUBLE_EQ(four.block.layers[0].youngs_modulus, 1e9);
}

}  // namespace

namespace {

TEST(IndentationCase, ToughnessFromTwoInsertions) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "needlekit-case-toughness";
  std::filesystem::create_directories(dir);
  // First insertion F = 2x, second F' = x (x in mm, F in N) over 1 mm: ∫(F - F') dx = 0.5 N·mm = 5e-4 J.
  std::ofstream(dir / "first.csv") << "depth_mm,force_N,comment\n0,0,a\n0.5,1,b\n1,2,c\n";
  std::ofstream(dir / "second.csv") << "depth_um,force_mN\n0,0\n1000,1000\n";
  const std::string text = test::replaced(kCase, "toughness = \"100 J/m2\"",
                                          "toughness_from = { first = \"first.csv\", second = \"second.csv\" }");
  std::ofstream(dir / "case.toml") << text;
  const insertion::IndentationCase c = io::read_indentation_case(dir / "case.toml");
  const double tip_area = M_PI / 4 * 230e-6 * 230e-6;  // the default crack area: the cylinder's tip
  ASSERT_TRUE(c.puncture.toughness.has_value());
  EXPECT_NEAR(*c.puncture.toughness, 5e-4 / tip_area, 1e-9 * 5e-4 / tip_area);

  std::ofstream(dir / "second.csv") << "depth,force_mN\n0,0\n1000,1000\n";
  try {
    io::read_indentation_case(dir / "case.toml");
    ADD_FAILURE() << "no error for a header without a unit";
  } catch (const InvalidInput& error) {
    EXPECT_THAT(error.what(), HasSubstr("second.csv:1: column 'depth' is not a depth with its unit"));
    EXPECT_THAT(error.what(), HasSubstr("case.toml:36:"));
  }
  std::ofstream(dir / "second.csv") << "depth_um,force_mN\n0,0\n0,1000\n";
  EXPECT_THROW(io::read_indentation_case(dir / "case.toml"), InvalidInput);
  std::filesystem::remove_all(dir);
}

}  // namespace

namespace {

// [loading] angle and azimuth (angled insertion): SI radians from degrees, the needle placed tilted with its lowest
// point at the surface and moving along its axis; a tilt under the tip-node rule, an angle of 90 deg or more, or a
// bare number are input errors naming the key and its line.
TEST(IndentationCase, AngleAndAzimuthTiltTheNeedle) {
  const std::string surface = replaced(kCase, "contact = \"tip-nodes\"", "contact = \"surface\"");
  const std::string angled = replaced(surface, "steps = 20\n", "steps = 20\nangle = \"30 deg\"\nazimuth = \"90 deg\"\n");
  const insertion::IndentationCase c = parse(angled);
  EXPECT_NEAR(c.angle, M_PI / 6, 1e-15);
  EXPECT_NEAR(c.azimuth, M_PI / 2, 1e-15);
  const Eigen::Vector3d axis = insertion::needle_axis(c);
  EXPECT_NEAR((axis - Eigen::Vector3d(0, 0.5, -std::sqrt(3.0) / 2)).norm(), 0, 1e-15) << "towards +y, 30 deg down";
  const std::vector<fem::Indenter> placed = insertion::placed_indenters(c);
  ASSERT_EQ(placed.size(), 1u);
  EXPECT_NEAR((placed[0].direction - axis).norm(), 0, 1e-15);
  double lowest = 1;
  for (const Eigen::Vector3d& v : placed[0].surface.vertices) lowest = std::min(lowest, v.z() - placed[0].edge_radius);
  // The sharp cylinder's lowest rim point is at the surface; the rounded one lies inside it, at most the edge radius
  // higher (the rim's rounding seen at 30 deg).
  EXPECT_GE(lowest, -1e-12);
  EXPECT_LT(lowest, placed[0].edge_radius);
  EXPECT_THAT(error_of(replaced(angled, "contact = \"surface\"", "contact = \"tip-nodes\"")),
              HasSubstr("key 'loading.angle': 30 deg with contact = \"tip-nodes\""));
  EXPECT_THAT(error_of(replaced(angled, "angle = \"30 deg\"", "angle = \"90 deg\"")),
              HasSubstr("case.toml:28: key 'loading.angle': 90 deg is outside [0, 90) deg"));
  EXPECT_THAT(error_of(replaced(angled, "angle = \"30 deg\"", "angle = 30")),
              HasSubstr("case.toml:28: key 'loading.angle'"));
  EXPECT_THAT(error_of(replaced(angled, "angle = \"30 deg\"", "angle = \"30 um\"")),
              HasSubstr("case.toml:28: key 'loading.angle'"));
  // Upright with the tip-node rule stays valid.
  EXPECT_NO_THROW(parse(replaced(kCase, "steps = 20\n", "steps = 20\nangle = \"0 deg\"\n")));
}

}  // namespace
