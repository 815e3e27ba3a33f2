// The indentation runner (§3.4-3.5) end to end on coarse Gmsh blocks: a flat punch follows Sneddon's half-space
// solution, the needles' work is stored as strain energy, the run stops at the step where the critical pressure is
// crossed, a solver failure keeps the completed steps, and the ParaView files read back with meshio.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/file_bytes.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/indentation_output.hpp"
#include "needlekit/io/view_arrays.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"
#include "../support/test_text.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

constexpr double kE = 0.2e6, kNu = 0.49, kRadius = 115e-6;  // §6.2 silicone rubber, 230 um punch

// A 230 um flat cylinder into a homogeneous block (silicone rubber unless told), coarse enough for a test.
insertion::IndentationCase flat_punch_case(double height, double depth, int steps, double nu = kNu) {
  insertion::IndentationCase c;
  c.name = "punch";
  needle::NeedleGeometry cylinder{needle::Shape::Cylinder, 2 * kRadius, 2 * kRadius, 0, 1000e-6};
  c.geometry = cylinder;
  c.needle = needle::needle_surface_mesh(cylinder, {32, 4});
  c.block.width = 3000e-6;
  c.block.length = 3000e-6;
  c.block.layers = {{"silicone rubber", height, kE, nu}};
  c.block.size_at_site = 40e-6;
  c.block.refinement_radius = 250e-6;
  c.block.size_far = 500e-6;
  c.block.threads = 1;
  c.depth = depth;
  c.steps = steps;
  c.solver.law = fem::MaterialLaw::NeoHookean;
  c.solver.contact = fem::ContactModel::TipNodes;
  c.solver.order = fem::ElementOrder::Linear;
  return c;
}

std::string fmt_steps(std::size_t n) { return std::to_string(n) + (n == 1 ? " completed step kept" : " completed steps kept"); }

double sneddon_force(double depth, double nu = kNu) { return 2 * kRadius * kE * depth / (1 - nu * nu); }  // Sneddon

// Linear tetrahedra at nu = 0.3 (no locking) keep this test fast; the nu = 0.49 quadratic case is the flat-punch
// example's test (tests/example/test_indent_cli.cpp).
TEST(Indentation, FlatPunchFollowsSneddonAndStoresTheWork) {
  constexpr double nu = 0.3;
  const insertion::IndentationCase c = flat_punch_case(3000e-6, 10e-6, 2, nu);
  int progress_calls = 0;
  insertion::IndentationOptions options;
  options.progress = [&](const insertion::IndentationProgress& p) {
    EXPECT_GE(p.fraction, 0.0);
    EXPECT_LE(p.fraction, 1.0);
    ++progress_calls;
  };
  const insertion::IndentationResult result = insertion::run_indentation(c, options);
  ASSERT_EQ(result.status, insertion::IndentationStatus::ReachedDepth) << result.reason;
  ASSERT_EQ(result.steps.size(), 2u);
  EXPECT_GT(progress_calls, 2);
  EXPECT_GT(result.elements, 1000);
  for (const insertion::IndentationStep& step : result.steps) {
    // Finite block (26 a deep, 13 a to the fixed sides) and a coarse mesh: within 12 % of the half-space.
    EXPECT_NEAR(step.force / sneddon_force(step.depth, nu), 1.0, 0.12) << "depth " << step.depth;
    // Quasi-static, conservative: the work of the needle is stored (trapezoidal work, 2 steps: ~1e-3).
    EXPECT_NEAR(step.external_work / step.strain_energy, 1.0, 0.02);
    // The contact area is the punch face (tributary areas of the nodes under it).
    EXPECT_NEAR(step.contact_area / (M_PI * kRadius * kRadius), 1.0, 0.35);
  }
  EXPECT_NEAR(result.steps[1].force / result.steps[0].force, 2.0, 0.02);  // linear at small depth
  // Solver statistics per step: the first step factorizes, every step takes a Newton solve, and the factorization
  // is reused (CG, or the projection on earlier solutions alone) rather than renewed for every solve.
  EXPECT_GE(result.steps[0].factorizations, 1);
  int solves = 0, factorizations = 0;
  for (const insertion::IndentationStep& step : result.steps) {
    EXPECT_GE(step.newton_iterations, 1);
    solves += step.newton_iterations;
    factorizations += step.factorizations;
  }
  EXPECT_LT(factorizations, solves);
  const insertion::PrePunctureCurve curve = insertion::pre_puncture_curve(result);
  ASSERT_EQ(curve.curve.depth.size(), 3u);
  EXPECT_EQ(curve.curve.depth[0], 0.0);
  EXPECT_FALSE(curve.puncture.has_value());
}

TEST(Indentation, APunctureInTheFirstStepIsLocatedInsideIt) {
  // Two steps of 20 um; P_c at 30 % of the first step's mean tip pressure. The pressure under a flat punch grows
  // linearly with depth, so the crossing is at about 6 um: found by bisecting the first step from the undeformed
  // state, not reported at the step's end (20 um).
  insertion::IndentationCase c = flat_punch_case(1150e-6, 40e-6, 2, 0.3);
  const insertion::IndentationResult reference = insertion::run_indentation(c);
  ASSERT_EQ(reference.status, insertion::IndentationStatus::ReachedDepth) << reference.reason;
  const insertion::IndentationStep& first = reference.steps.front();
  c.puncture.critical_pressure = 0.3 * first.contact_pressure;
  const insertion::IndentationResult result = insertion::run_indentation(c);
  ASSERT_EQ(result.status, insertion::IndentationStatus::Punctured) << result.reason;
  ASSERT_EQ(result.steps.size(), 1u);
  EXPECT_NEAR(result.puncture->depth / first.depth, 0.3, 0.02);
  EXPECT_NEAR(result.puncture->force / first.force, 0.3, 0.02);
}

TEST(Indentation, StopsAtTheStepThatCrossesTheCriticalPressure) {
  insertion::IndentationCase c = flat_punch_case(1150e-6, 40e-6, 8);
  // P = F/A grows about linearly; pick P_c at 60 % of the Sneddon pressure at full depth.
  c.puncture.critical_pressure = 0.6 * sneddon_force(c.depth) / (M_PI * kRadius * kRadius);
  const insertion::IndentationResult result = insertion::run_indentation(c);
  ASSERT_EQ(result.status, insertion::IndentationStatus::Punctured) << result.reason;
  ASSERT_TRUE(result.puncture.has_value());
  EXPECT_EQ(result.puncture->criterion, insertion::PunctureCriterion::CriticalPressure);
  ASSERT_GE(result.steps.size(), 2u);
  EXPECT_LT(result.steps.size(), 8u);  // stopped before the final depth
  const auto& last = result.steps.back();
  const auto& before = result.steps[result.steps.size() - 2];
  EXPECT_GE(last.contact_pressure, *c.puncture.critical_pressure);
  EXPECT_LT(before.contact_pressure, *c.puncture.critical_pressure);
  EXPECT_GT(result.puncture->depth, before.depth);
  EXPECT_LE(result.puncture->depth, last.depth);
  EXPECT_GT(result.puncture->force, before.force);
  EXPECT_LE(result.puncture->force, last.force);
  EXPECT_THAT(result.reason, HasSubstr("critical-pressure"));
}

// St Venant-Kirchhoff fails under large compression (an element inverts): a 230 um punch pushed 280 um into a
// 300 um layer stops after the first step(s) with the reason, and the converged steps are kept: the full load steps
// and, last, the deepest state that the failed step's cut-backs reached, inside that step.
TEST(Indentation, SolverFailureKeepsTheCompletedSteps) {
  insertion::IndentationCase c = flat_punch_case(300e-6, 280e-6, 7, 0.3);
  c.solver.law = fem::MaterialLaw::StVenantKirchhoff;
  const insertion::IndentationResult result = insertion::run_indentation(c);
  ASSERT_EQ(result.status, insertion::IndentationStatus::SolverFailed) << result.reason;
  EXPECT_THAT(result.reason, HasSubstr("did not converge"));
  EXPECT_THAT(result.reason, HasSubstr(fmt_steps(result.steps.size())));
  EXPECT_THAT(result.reason, HasSubstr("tetrahedron "));  // which element inverted, and where
  EXPECT_THAT(result.reason, HasSubstr("below the top surface"));
  ASSERT_GE(result.steps.size(), 2u);
  EXPECT_LT(result.steps.size(), 7u);
  const std::size_t full = result.steps.size() - 1;
  EXPECT_THAT(result.reason, HasSubstr("the step's deepest converged state at"));
  for (std::size_t k = 0; k < result.steps.size(); ++k) {
    if (k < full) EXPECT_NEAR(result.steps[k].depth, 40e-6 * static_cast<double>(k + 1), 1e-12);
    EXPECT_GT(result.steps[k].force, k == 0 ? 0.0 : result.steps[k - 1].force);
  }
  EXPECT_GT(result.steps[full].depth, 40e-6 * static_cast<double>(full));
  EXPECT_LT(result.steps[full].depth, 40e-6 * static_cast<double>(full + 1));
  EXPECT_FALSE(result.puncture.has_value());
  EXPECT_EQ(insertion::pre_puncture_curve(result).curve.depth.size(), result.steps.size() + 1);
}

TEST(Indentation, RejectsANeedleInsideTheTissue) {
  insertion::IndentationCase c = flat_punch_case(1150e-6, 20e-6, 4);
  c.needles[0].tip_height = -5e-6;
  EXPECT_THAT([&] { insertion::run_indentation(c); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("needles[0].tip_height")));
}

// meshio's view of a .vtu: field names with their shapes and value ranges, and the cell types.
nlohmann::json summary_with_meshio(const std::filesystem::path& file) {
  const auto script = file.parent_path() / "summary.py";
  std::ofstream(script) << R"(import json, sys, meshio
m = meshio.read(sys.argv[1])
def s(v): return {"shape": list(v.shape), "min": float(v.min()), "max": float(v.max())}
print(json.dumps({
  "points": len(m.points),
  "cells": {b.type: len(b.data) for b in m.cells},
  "point_data": {k: s(v) for k, v in m.point_data.items()},
  "cell_data": {k: s(v[0]) for k, v in m.cell_data.items()},
  "contact_uz": s(m.point_data["displacement_m"][m.point_data["contact_flag"].ravel() > 0, 2])
      if "contact_flag" in m.point_data else None,
}))
)";
  return nlohmann::json::parse(test::command_output("/usr/bin/python3 " + script.string() + " " + file.string()));
}

TEST(Indentation, ParaViewSeriesReadsBackWithMeshio) {
  insertion::IndentationCase c = flat_punch_case(1150e-6, 10e-6, 2);
  c.block.layers = {{"stiff top", 100e-6, 1e6, 0.4}, {"soft", 1050e-6, kE, kNu}};
  const auto dir = std::filesystem::temp_directory_path() / ("needlekit-indent-vtu-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  io::IndentationWriter writer(dir, c);
  writer.write_view({NEEDLEKIT_SOURCE_DIR "/web/viewer"});
  insertion::IndentationOptions options;
  options.on_mesh = [&](const mesh::TetMesh& tissue) { writer.set_mesh(tissue); };
  options.on_step = [&](const insertion::IndentationStep& step, const fem::QuasiStaticSolver& solver) {
    writer.write_step(step, solver);
  };
  const insertion::IndentationResult result = insertion::run_indentation(c, options);
  writer.finish(result);
  ASSERT_EQ(result.steps.size(), 2u) << result.reason;
  ASSERT_TRUE(std::filesystem::exists(dir / "punch.pvd"));
  ASSERT_TRUE(std::filesystem::exists(dir / "punch_force_depth.csv"));
  ASSERT_TRUE(std::filesystem::exists(dir / "punch_puncture.json"));

  const nlohmann::json vtu = summary_with_meshio(dir / "punch_step_002.vtu");
  EXPECT_EQ(vtu["points"].get<int>(), result.nodes);
  EXPECT_EQ(vtu["cells"]["tetra"].get<int>(), result.elements);
  // The nodes under the punch moved down with it by the full depth.
  EXPECT_NEAR(vtu["contact_uz"]["min"].get<double>(), -10e-6, 1e-12);
  EXPECT_NEAR(vtu["contact_uz"]["max"].get<double>(), -10e-6, 1e-12);
  EXPECT_EQ(vtu["point_data"]["displacement_m"]["shape"][1].get<int>(), 3);
  EXPECT_EQ(vtu["point_data"]["contact_flag"]["max"].get<double>(), 1.0);
  EXPECT_GT(vtu["point_data"]["contact_pressure_Pa"]["max"].get<double>(), 0.0);
  EXPECT_EQ(vtu["cell_data"]["cauchy_stress_Pa"]["shape"][1].get<int>(), 9);
  EXPECT_GT(vtu["cell_data"]["von_mises_stress_Pa"]["max"].get<double>(), 0.0);
  EXPECT_GT(vtu["cell_data"]["strain_energy_density_J_per_m3"]["max"].get<double>(), 0.0);
  EXPECT_EQ(vtu["cell_data"]["layer_id"]["min"].get<double>(), 0.0);
  EXPECT_EQ(vtu["cell_data"]["layer_id"]["max"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(vtu["cell_data"]["youngs_modulus_Pa"]["max"].get<double>(), 1e6);
  EXPECT_DOUBLE_EQ(vtu["cell_data"]["youngs_modulus_Pa"]["min"].get<double>(), kE);
  EXPECT_DOUBLE_EQ(vtu["cell_data"]["poisson_ratio"]["max"].get<double>(), kNu);

  const nlohmann::json needles = summary_with_meshio(dir / "punch_needles_step_002.vtu");
  EXPECT_GT(needles["cells"]["triangle"].get<int>(), 0);

  std::ifstream csv(dir / "punch_force_depth.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_THAT(header, HasSubstr("depth_um,force_N,"));

  // The 3D view of the same run (docs/views.md): at step 2 the top-surface vertices under the punch are 10 um down,
  // have moved by at least that much and carry contact pressure (compressive on the whole: a prescribed node of the
  // tip-nodes rule may pull near the punch's edge).
  ASSERT_TRUE(std::filesystem::exists(dir / "punch_view.html"));
  ASSERT_TRUE(std::filesystem::exists(dir / "viewer" / "three.min.js"));
  const std::string script = read_file_bytes(dir / "punch_view.js", "view");
  const nlohmann::json view = nlohmann::json::parse(script.substr(script.find(".push(") + 6, script.rfind(')') -
                                                                                               script.find(".push(") - 6));
  ASSERT_EQ(view["steps"].size(), 2u);
  const std::size_t vertices = view["surface"]["vertices"].get<std::size_t>();
  const std::vector<double> xyz = io::decoded_array(view["surface"]["positions"]);
  const std::vector<double> u = io::decoded_array(view["surface"]["fields"][0]["values"]);
  const std::vector<double> p = io::decoded_array(view["surface"]["fields"][2]["values"]);
  int under = 0;
  double pressure = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::size_t k = vertices + v;  // step 2
    if (std::hypot(xyz[3 * k], xyz[3 * k + 1]) > 0.8 * kRadius || xyz[3 * k + 2] < -50e-6) continue;
    ++under;
    EXPECT_NEAR(xyz[3 * k + 2], -10e-6, 1.2e-3 / 65535);
    EXPECT_GE(u[k], 10e-6 * (1 - 1e-3));
    EXPECT_NE(p[k], 0.0);
    pressure += p[k];
  }
  EXPECT_GT(under, 3);
  EXPECT_GT(pressure, 0.0);
  std::filesystem::remove_all(dir);
}

}  // namespace

// Warm start (calibration's finite differences, issue 13): E 0.1 % higher, every load step started from the first
// run's field at the same depth. The forces are those of a cold run to the Newton tolerance, in fewer iterations;
// a surface-contact run warm-starts too.
TEST(Indentation, WarmStartGivesTheColdForcesInFewerIterations) {
  for (const fem::ContactModel contact : {fem::ContactModel::TipNodes, fem::ContactModel::Surface}) {
    insertion::IndentationCase c = flat_punch_case(1150e-6, 60e-6, 4, 0.3);
    c.solver.contact = contact;
    insertion::IndentationOptions keep;
    keep.keep_displacements = true;
    const insertion::IndentationResult base = insertion::run_indentation(c, keep);
    ASSERT_EQ(base.displacements.size(), 4u) << base.reason;
    c.block.layers[0].youngs_modulus *= 1.001;
    const insertion::IndentationResult cold = insertion::run_indentation(c);
    insertion::IndentationOptions warm_options;
    warm_options.warm_start = &base.displacements;
    const insertion::IndentationResult warm = insertion::run_indentation(c, warm_options);
    ASSERT_EQ(warm.steps.size(), cold.steps.size()) << cold.reason;
    EXPECT_EQ(warm.warm_started_steps, 4);
    EXPECT_EQ(cold.warm_started_steps, 0);
    int cold_iterations = 0, warm_iterations = 0;
    for (std::size_t k = 0; k < cold.steps.size(); ++k) {
      EXPECT_NEAR(warm.steps[k].force, cold.steps[k].force, 1e-5 * cold.steps[k].force) << "step " << k;
      cold_iterations += cold.steps[k].newton_iterations;
      warm_iterations += warm.steps[k].newton_iterations;
    }
    EXPECT_LT(warm_iterations, cold_iterations) << "contact " << fem::to_string(contact);
  }
}
