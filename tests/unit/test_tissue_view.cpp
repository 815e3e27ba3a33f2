// The report's 3D views (docs/views.md): the tissue's boundary surface (closed, every edge shared by two faces,
// Euler characteristic 2, the face count of a structured block, outward normals), the per-vertex fields at known
// nodes, the base64 typed arrays read back, and the 5 MB bound of a 300k-tetrahedron run's view.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <random>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/indentation_view.hpp"
#include "needlekit/io/patch_view.hpp"
#include "needlekit/io/tissue_view_surface.hpp"
#include "needlekit/io/view_arrays.hpp"
#include "needlekit/io/view_page.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

mesh::TetMesh block(int nx, int ny, int nz, double size = 1e-3) {
  mesh::StructuredBlockOptions o;
  o.width = o.length = o.height = size;
  o.nx = nx;
  o.ny = ny;
  o.nz = nz;
  return mesh::structured_block_mesh(o);
}

std::vector<std::uint8_t> bytes_of(std::string_view text) { return {text.begin(), text.end()}; }

// How many faces use each undirected edge, and whether each directed edge is used once (consistent orientation).
struct EdgeUse {
  std::map<std::pair<int, int>, int> undirected;
  std::map<std::pair<int, int>, int> directed;
};

EdgeUse edge_use(const io::TissueViewSurface& s) {
  EdgeUse use;
  for (const auto& t : s.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = static_cast<int>(t[k]), b = static_cast<int>(t[(k + 1) % 3]);
      ++use.undirected[{std::min(a, b), std::max(a, b)}];
      ++use.directed[{a, b}];
    }
  }
  return use;
}

insertion::IndentationCase cylinder_case(int needles) {
  insertion::IndentationCase c;
  c.name = "view";
  const needle::NeedleGeometry cylinder{needle::Shape::Cylinder, 100e-6, 100e-6, 0, 500e-6};
  c.needle = needle::needle_surface_mesh(cylinder, {16, 2});
  c.needles.clear();
  for (int n = 0; n < needles; ++n) c.needles.push_back({Eigen::Vector2d(200e-6 * n, 0), 0});
  return c;
}

}  // namespace

TEST(ViewArrays, Base64OfTheRfc4648Vectors) {
  const std::vector<std::pair<std::string, std::string>> vectors = {
      {"", ""}, {"f", "Zg=="}, {"fo", "Zm8="}, {"foo", "Zm9v"}, {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="},
      {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    EXPECT_EQ(io::base64_encode(bytes_of(plain)), encoded);
    EXPECT_EQ(io::base64_decode(encoded), bytes_of(plain));
  }
  std::mt19937 random(7);
  std::vector<std::uint8_t> bytes(1001);
  for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(random());
  EXPECT_EQ(io::base64_decode(io::base64_encode(bytes)), bytes);
  EXPECT_THROW(io::base64_decode("Zm9"), InvalidInput);
  EXPECT_THAT([] { io::base64_decode("Zm*v"); }, testing::ThrowsMessage<InvalidInput>(HasSubstr("'*'")));
}

TEST(ViewArrays, TypedArraysReadBackExactlyAndQuantizedWithinHalfACode) {
  const std::vector<float> values = {0.0f, -1.5e-6f, 3.25f, 1e-30f, -7e8f};
  EXPECT_EQ(io::decoded_array(io::float32_array(values)), std::vector<double>(values.begin(), values.end()));
  const std::vector<std::uint32_t> indices = {0, 1, 4294967295u, 123456789};
  EXPECT_EQ(io::decoded_array(io::uint32_array(indices)), std::vector<double>(indices.begin(), indices.end()));

  // Three components with their own ranges (µm-scale x, m-scale y, a constant z).
  std::vector<float> xyz;
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(0, 1);
  for (int k = 0; k < 500; ++k) xyz.insert(xyz.end(), {1e-6f * unit(random), 2.0f * unit(random) - 1, 0.25f});
  const nlohmann::json q = io::quantized_array(xyz, 3);
  EXPECT_EQ(q["dtype"], "uint16");
  EXPECT_EQ(io::base64_decode(q["base64"].get<std::string>()).size(), 2 * xyz.size());
  const std::vector<double> back = io::decoded_array(q);
  ASSERT_EQ(back.size(), xyz.size());
  for (std::size_t k = 0; k < xyz.size(); ++k) {
    const int c = static_cast<int>(k % 3);
    const double range = q["hi"][c].get<double>() - q["lo"][c].get<double>();
    EXPECT_LE(std::abs(back[k] - xyz[k]), range / 131070 * 1.001 + 1e-7 * std::abs(xyz[k])) << k;
  }
}

TEST(TissueViewSurface, AStructuredBlocksBoundaryIsClosedWithTwoTrianglesPerQuad) {
  for (const auto& [nx, ny, nz] : {std::tuple{1, 1, 1}, std::tuple{3, 2, 4}, std::tuple{6, 5, 3}}) {
    const mesh::TetMesh tissue = block(nx, ny, nz);
    const io::TissueViewSurface s = io::tissue_view_surface(tissue);
    EXPECT_EQ(s.triangles.size(), 4u * (nx * ny + ny * nz + nx * nz));
    EXPECT_EQ(s.nodes.size(), static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1) - (nx - 1) * (ny - 1) * (nz - 1)));
    const EdgeUse use = edge_use(s);
    for (const auto& [edge, count] : use.undirected) EXPECT_EQ(count, 2);
    for (const auto& [edge, count] : use.directed) EXPECT_EQ(count, 1);  // consistently oriented
    const long euler = static_cast<long>(s.nodes.size()) - static_cast<long>(use.undirected.size()) +
                       static_cast<long>(s.triangles.size());
    EXPECT_EQ(euler, 2);
    // Outward: the divergence theorem gives the block's volume (1 mm^3) from the surface.
    double volume = 0;
    for (const auto& t : s.triangles) {
      const Eigen::Vector3d& a = tissue.nodes[s.nodes[t[0]]];
      const Eigen::Vector3d& b = tissue.nodes[s.nodes[t[1]]];
      const Eigen::Vector3d& c = tissue.nodes[s.nodes[t[2]]];
      volume += a.dot(b.cross(c)) / 6;
    }
    EXPECT_NEAR(volume, 1e-9, 1e-9 * 1e-9);
    const io::TissueViewSurface top = io::top_surface(s, tissue);
    EXPECT_EQ(top.triangles.size(), 2u * nx * ny);
    EXPECT_EQ(top.nodes.size(), static_cast<std::size_t>((nx + 1) * (ny + 1)));
    for (int n : top.nodes) EXPECT_EQ(tissue.nodes[n].z(), 0.0);
  }
}

TEST(TissueViewSurface, FieldsAtKnownNodes) {
  const mesh::TetMesh tissue = block(4, 4, 4);
  const io::TissueViewSurface s = io::tissue_view_surface(tissue);
  // u = (0, 0, -0.01 (x + 0.5 mm)), pressure = 1000 x node index, von Mises 1 kPa in the top half, 3 kPa below.
  std::vector<Eigen::Vector3d> u;
  std::vector<double> pressure;
  for (std::size_t n = 0; n < tissue.nodes.size(); ++n) {
    u.emplace_back(0, 0, -0.01 * (tissue.nodes[n].x() + 0.5e-3));
    pressure.push_back(1000.0 * n);
  }
  std::vector<double> von_mises;
  for (const auto& t : tissue.tets) {
    double z = 0;
    for (int n : t) z += tissue.nodes[n].z() / 4;
    von_mises.push_back(z > -0.5e-3 ? 1e3 : 3e3);
  }
  const io::SurfaceStep step = io::surface_step(s, tissue, u, pressure, von_mises);
  ASSERT_EQ(step.positions.size(), 3 * s.nodes.size());
  for (std::size_t v = 0; v < s.nodes.size(); ++v) {
    const int n = s.nodes[v];
    const Eigen::Vector3d p = tissue.nodes[n] + u[n];
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(step.positions[3 * v + c], static_cast<float>(p[c]));
    EXPECT_FLOAT_EQ(step.displacement[v], static_cast<float>(u[n].norm()));
    EXPECT_FLOAT_EQ(step.contact_pressure[v], static_cast<float>(pressure[n]));
    const double z = tissue.nodes[n].z();
    if (z == 0) {
      EXPECT_FLOAT_EQ(step.von_mises_stress[v], 1e3f);  // only top-half tetrahedra
    } else if (std::abs(z + 1e-3) < 1e-12) {
      EXPECT_FLOAT_EQ(step.von_mises_stress[v], 3e3f);  // only bottom-half tetrahedra
    } else if (std::abs(z + 0.5e-3) < 1e-12) {          // both: a volume-weighted mean
      EXPECT_GT(step.von_mises_stress[v], 1e3f);
      EXPECT_LT(step.von_mises_stress[v], 3e3f);
    }
  }
  EXPECT_THROW(io::nodal_average(tissue, std::vector<double>(3, 0.0)), InvalidInput);
}

namespace {

// Three steps of two needles pushed k um down (the whole block moving with them), 0.04 k N and 0.06 k N on each.
void add_three_steps(io::IndentationView& view, const mesh::TetMesh& tissue) {
  view.set_mesh(tissue);
  std::vector<double> zero_pressure(tissue.nodes.size(), 0.0), stress(tissue.tets.size(), 5.0);
  for (int k = 1; k <= 3; ++k) {
    std::vector<Eigen::Vector3d> u(tissue.nodes.size(), Eigen::Vector3d(0, 0, -1e-6 * k));
    insertion::IndentationStep step;
    step.depth = 1e-6 * k;
    step.force = 0.1 * k;
    step.needle_force = {0.04 * k, 0.06 * k};
    view.add_step(step, 1e-6 * k, io::surface_step(view.surface(), tissue, u, zero_pressure, stress));
  }
}

}  // namespace

TEST(IndentationView, StepsNeedlesAndTheTableInTheView) {
  const mesh::TetMesh tissue = block(4, 4, 2);
  const insertion::IndentationCase c = cylinder_case(2);
  io::IndentationView view(c);
  add_three_steps(view, tissue);
  const nlohmann::json json = view.json();
  EXPECT_EQ(json["kind"], "indentation");
  EXPECT_EQ(json["steps"].size(), 3u);
  EXPECT_EQ(json["surface"]["region"], "boundary");
  const std::vector<double> positions = io::decoded_array(json["surface"]["positions"]);
  ASSERT_EQ(positions.size(), 3 * 3 * view.surface().nodes.size());
  // Step 2's z of the first surface vertex: its reference z − 2 um (to 16 bits of the 1 mm range).
  const std::size_t v = view.surface().nodes.size();
  EXPECT_NEAR(positions[3 * v + 2], tissue.nodes[view.surface().nodes[0]].z() - 2e-6, 1e-3 / 65535);
  EXPECT_EQ(json["surface"]["fields"].size(), 3u);
  EXPECT_EQ(json["surface"]["fields"][1]["key"], "von_mises_stress_Pa");
  EXPECT_EQ(json["needles"]["instances"].size(), 2u);
  EXPECT_EQ(json["needles"]["meshes"].size(), 1u);  // the second needle is the first one moved
  EXPECT_NEAR(json["needles"]["instances"][1]["offset"][0].get<double>(), 200e-6, 1e-10);  // Float32
  EXPECT_EQ(json["needles"]["displacement_m"].size(), 3u);
  EXPECT_NEAR(json["needles"]["table"]["rows"][1][4][2].get<double>(), 0.18, 1e-12);  // needle 2's force at step 3
  const std::string script = io::view_script(json);
  EXPECT_THAT(script, testing::StartsWith("(window.needlekitViews = window.needlekitViews || []).push({"));
}

// An array's view: after set_outcomes each needle's row holds its puncture state, tip depth and inserted depth at every
// stored step, the step it punctured in and its puncture depth.
TEST(IndentationView, EachNeedlesPunctureStateAndDepthFollowTheSteps) {
  const mesh::TetMesh tissue = block(4, 4, 2);
  const insertion::IndentationCase c = cylinder_case(2);
  io::IndentationView view(c);
  add_three_steps(view, tissue);
  std::vector<insertion::NeedleOutcome> outcomes(2);
  outcomes[0].depth = {1e-6, 2e-6, 3e-6};
  outcomes[1].depth = {0.5e-6, 1e-6, 1.5e-6};
  outcomes[0].puncture_step = 2;  // needle 1 punctures in step 2 at 1.5 um and travels 1.5 um further
  outcomes[0].puncture = insertion::PuncturePoint{1.5e-6, 0.07, insertion::PunctureCriterion::CriticalPressure};
  outcomes[0].inserted_depth = 1.5e-6;
  view.set_outcomes(outcomes);
  const nlohmann::json table = view.json()["needles"]["table"];
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < table["columns"].size(); ++i) column[table["columns"][i]["key"]] = i;
  ASSERT_EQ(table["columns"].size(), 10u);
  EXPECT_EQ(table["columns"][column["inserted_depth_um"]]["colour"], true);
  const nlohmann::json& first = table["rows"][0];
  const nlohmann::json& second = table["rows"][1];
  EXPECT_EQ(first[column["status"]], nlohmann::json({"intact", "punctured", "punctured"}));
  EXPECT_EQ(second[column["status"]], nlohmann::json({"intact", "intact", "intact"}));
  EXPECT_NEAR(first[column["depth_um"]][2].get<double>(), 3.0, 1e-9);
  EXPECT_NEAR(second[column["depth_um"]][1].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(first[column["puncture_step"]], 2);
  EXPECT_TRUE(second[column["puncture_step"]].is_null());
  EXPECT_NEAR(first[column["puncture_depth_um"]].get<double>(), 1.5, 1e-9);
  // Inserted: 0 before the puncture, then the travel beyond 1.5 um; at the last step the outcome's inserted depth.
  EXPECT_EQ(first[column["inserted_depth_um"]][0], 0.0);
  EXPECT_NEAR(first[column["inserted_depth_um"]][1].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(first[column["inserted_depth_um"]][2].get<double>(), outcomes[0].inserted_depth * 1e6, 1e-9);
  EXPECT_EQ(second[column["inserted_depth_um"]], nlohmann::json({0.0, 0.0, 0.0}));
}

// A 300k-tetrahedron block (60 x 60 x 14 hexes x 6) with 30 load steps stays within 5 MB; a smaller budget keeps the
// top surface and drops steps, and the file still fits.
TEST(IndentationView, AThreeHundredThousandTetrahedronRunFitsInFiveMegabytes) {
  mesh::StructuredBlockOptions o;
  o.width = o.length = 3e-3;
  o.height = 1e-3;
  o.nx = o.ny = 60;
  o.nz = 14;
  const mesh::TetMesh tissue = mesh::structured_block_mesh(o);
  ASSERT_GE(tissue.tets.size(), 300'000u);
  const insertion::IndentationCase c = cylinder_case(1);
  for (const double budget : {5e6, 0.5e6}) {
    io::IndentationView view(c, {budget});
    view.set_mesh(tissue);
    const std::vector<double> stress(tissue.tets.size(), 1e4);
    for (int k = 1; k <= 30; ++k) {
      std::vector<Eigen::Vector3d> u(tissue.nodes.size());
      std::vector<double> pressure(tissue.nodes.size());
      for (std::size_t n = 0; n < u.size(); ++n) {
        const double r = tissue.nodes[n].head<2>().norm();
        u[n] = Eigen::Vector3d(0, 0, -1e-6 * k * std::exp(-r / 3e-4));
        pressure[n] = r < 1e-4 ? 1e5 * k : 0;
      }
      insertion::IndentationStep step;
      step.depth = 1e-6 * k;
      view.add_step(step, step.depth, io::surface_step(view.surface(), tissue, u, pressure, stress));
    }
    const nlohmann::json json = view.json();
    const std::size_t bytes = io::view_script(json).size();
    EXPECT_LE(bytes, budget) << json["steps"].size() << " steps of " << json["surface"]["region"];
    EXPECT_GE(json["steps"].size(), 2u);
    EXPECT_NEAR(json["steps"].back()["depth_um"].get<double>(), 30.0, 1e-9);  // the last step is always kept
    if (budget < 1e6) {
      EXPECT_EQ(json["surface"]["region"], "top");
      EXPECT_LT(json["steps"].size(), 30u);
      EXPECT_EQ(json["notes"].size(), 2u);
    } else {
      EXPECT_EQ(json["surface"]["region"], "boundary");
    }
  }
}

TEST(ViewPage, ThePageLoadsTheViewerAndTheDataFiles) {
  const std::string page = io::view_page("a <b>", {"x_view.js"});
  EXPECT_THAT(page, HasSubstr("<title>a &lt;b&gt;</title>"));
  EXPECT_THAT(page, HasSubstr("<script src=\"viewer/three.min.js\"></script>"));
  EXPECT_THAT(page, HasSubstr("<script src=\"viewer/OrbitControls.js\"></script>"));
  EXPECT_THAT(page, HasSubstr("<script src=\"x_view.js\"></script>"));
  EXPECT_THAT([] { io::viewer_files({NEEDLEKIT_SOURCE_DIR "/web/viewer", "/nonexistent"}); },
              testing::ThrowsMessage<IoError>(HasSubstr("libjs-three")));
}
