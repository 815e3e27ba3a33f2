// Flat cylindrical punch on a thick block vs Sneddon's half-space solution F = 2aE delta / (1 - nu^2) (dissertation
// §3.4, §6.2's flat needle): convergence under refinement, locking of linear tetrahedra at nu = 0.49 and its removal
// by quadratic tetrahedra, agreement of the two laws at small strain, the energy balance of quasi-static loading, and
// the surface-contact model against the dissertation's tip-node rule. Quarter models (symmetry planes through the
// needle axis) keep each case to a few seconds.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <tbb/parallel_invoke.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "fem_test_support.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::test_support;

namespace {

constexpr double kA = 115e-6;    // m, punch radius (the 230 um flat needle of §6.2)
constexpr double kE = 0.2e6;     // Pa, silicone rubber phantom

struct PunchRun {
  StepResult result;
  double sneddon = 0;  // N, full punch
  double force = 0;    // N, full punch (4 x quarter)
  int newton_iterations = 0;  // over all steps (each one linear solve)
};

// `edge_radius` > 0 (surface contact): the punch's edges rounded with it, given to the solver as the eroded core
// (needle/rounded_edges.hpp) with its tip that radius above the surface.
PunchRun punch(double extent_over_a, int core, double nu, double depth, SolverOptions o = {}, int steps = 1,
               double radius_factor = 1.0, double edge_radius = 0) {
  const double extent = extent_over_a * kA;
  const auto mesh = quarter_punch_block(kA, extent, core, kE, nu);
  o.boundary = BoundaryCondition::QuarterSymmetry;
  const double corner = -extent / 2;
  const auto body = flat_cylinder(radius_factor * kA - edge_radius, 300e-6 - edge_radius);
  QuasiStaticSolver solver(mesh, {{placed_needle(body, corner, corner, edge_radius, 256), {0, 0, -1}, edge_radius}}, o);
  PunchRun run;
  for (int s = 1; s <= steps; ++s) {
    run.result = solver.advance_to(depth * s / steps);
    run.newton_iterations += run.result.newton_iterations;
  }
  run.force = 4 * run.result.indenter_force[0];
  run.sneddon = sneddon_flat_punch_force(kA, kE, nu, depth);
  return run;
}

TEST(FlatPunch, ConvergesToSneddonUnderRefinement) {
  // nu = 0.3, depth 1% of the radius; block 40 a; the nodes on the punch's edge r = a are under the tip. Conforming
  // displacement elements are too stiff, and the error falls about linearly with the core spacing (the punch edge
  // is a square-root stress singularity): F / F_Sneddon = 1.337, 1.233, 1.180 with 2, 3, 4 cells across a.
  std::vector<double> error;
  for (int core : {2, 3, 4}) {
    const auto run = punch(40, core, 0.3, 0.01 * kA);
    ASSERT_TRUE(run.result.converged) << run.result.reason;
    error.push_back(run.force / run.sneddon - 1);
  }
  EXPECT_GT(error[0], error[1]);
  EXPECT_GT(error[1], error[2]);
  EXPECT_GT(error[2], 0.0);
  const double order = std::log(error[0] / error[2]) / std::log(4.0 / 2.0);
  EXPECT_GT(order, 0.8) << "observed convergence order " << order;
  EXPECT_LT(error[2], 0.2) << "F / F_Sneddon - 1 on the finest mesh";
}

TEST(FlatPunch, QuadraticTetrahedraRemoveLockingAtNu049) {
  // nu = 0.49 (the §6.2 phantom) on one coarse mesh: linear tetrahedra lock and are far too stiff; quadratic
  // tetrahedra on the same mesh are close to Sneddon (the rest is the coarse mesh and the finite block).
  SolverOptions linear, quadratic;
  quadratic.order = ElementOrder::Quadratic;
  const auto lin = punch(10, 2, 0.49, 0.01 * kA, linear);
  const auto quad = punch(10, 2, 0.49, 0.01 * kA, quadratic);
  ASSERT_TRUE(lin.result.converged && quad.result.converged);
  const double lin_error = lin.force / lin.sneddon - 1, quad_error = quad.force / quad.sneddon - 1;
  EXPECT_GT(lin_error, 0.8) << "linear tetrahedra at nu = 0.49";
  EXPECT_LT(std::abs(quad_error), 0.35) << "quadratic tetrahedra at nu = 0.49";
  EXPECT_LT(std::abs(quad_error), 0.25 * lin_error);
  // Same mesh at nu = 0.3: the linear elements' excess stiffness is much smaller there (it is locking, not mesh).
  const auto lin03 = punch(10, 2, 0.3, 0.01 * kA, linear);
  EXPECT_LT(lin03.force / lin03.sneddon - 1, 0.5 * lin_error);
}

TEST(FlatPunch, LawsAgreeAtSmallStrainAndDifferAtLargeStrain) {
  SolverOptions svk, nh;
  nh.law = MaterialLaw::NeoHookean;
  const auto a = punch(10, 2, 0.4, 0.002 * kA, svk), b = punch(10, 2, 0.4, 0.002 * kA, nh);
  ASSERT_TRUE(a.result.converged && b.result.converged);
  EXPECT_NEAR(a.force / b.force, 1.0, 2e-3);
  const auto c = punch(10, 2, 0.4, 0.3 * kA, svk, 6), d = punch(10, 2, 0.4, 0.3 * kA, nh, 6);
  ASSERT_TRUE(c.result.converged && d.result.converged) << c.result.reason << d.result.reason;
  EXPECT_GT(std::abs(c.force / d.force - 1), 10 * std::abs(a.force / b.force - 1));
}

TEST(FlatPunch, ExternalWorkEqualsStoredEnergy) {
  // Quasi-static, conservative loading to 30% of the radius in 12 steps: the needle's work (trapezoidal rule over
  // the steps) equals the strain energy stored in the tissue.
  for (auto law : {MaterialLaw::StVenantKirchhoff, MaterialLaw::NeoHookean}) {
    SolverOptions o;
    o.law = law;
    const auto run = punch(10, 2, 0.4, 0.3 * kA, o, 12);
    ASSERT_TRUE(run.result.converged) << run.result.reason;
    EXPECT_NEAR(run.result.external_work / run.result.strain_energy, 1.0, 2e-3) << to_string(law);
    EXPECT_GT(run.result.strain_energy, 0);
  }
}

TEST(FlatPunch, PredictorAndLinearSolverDoNotChangeTheAnswer) {
  // Neo-Hookean to 30% of the radius in 6 steps: the secant predictor (default) against the linearised solve of
  // §3.4 before every step, and CG on a reused factorization (default) against a fresh factorization per solve.
  // Same converged states to the Newton tolerances; the secant predictor saves linear solves.
  SolverOptions fast, reference;
  fast.law = reference.law = MaterialLaw::NeoHookean;
  reference.extrapolate_predictor = false;
  reference.linear_solver = fem::LinearSolver::Cholesky;
  const auto a = punch(10, 2, 0.4, 0.3 * kA, fast, 6), b = punch(10, 2, 0.4, 0.3 * kA, reference, 6);
  ASSERT_TRUE(a.result.converged && b.result.converged) << a.result.reason << b.result.reason;
  EXPECT_NEAR(a.force / b.force, 1.0, 1e-5);
  EXPECT_NEAR(a.result.strain_energy / b.result.strain_energy, 1.0, 1e-5);
  EXPECT_LT(a.newton_iterations, b.newton_iterations);
}

TEST(FlatPunch, PredictorErrorIsThirdOrderInTheStep) {
  // From the third step on, the predictor extrapolates the last three converged states quadratically, so the
  // residual it leaves falls as h^3 with the step h (a linear extrapolation's as h^2). Neo-Hookean punch to 30 % of
  // the radius in 6 and in 12 steps: the residual at the start of the last step, which ends at the same depth.
  SolverOptions o;
  o.law = MaterialLaw::NeoHookean;
  const double depth = 0.3 * kA;
  std::vector<double> start_residual;
  for (int steps : {6, 12}) {
    const auto mesh = quarter_punch_block(kA, 10 * kA, 2, kE, 0.4);
    o.boundary = BoundaryCondition::QuarterSymmetry;
    const auto needle = placed_needle(flat_cylinder(kA, 300e-6), -5 * kA, -5 * kA, 0, 256);
    QuasiStaticSolver solver(mesh, {{needle, {0, 0, -1}, 0}}, o);
    StepResult last;
    for (int s = 1; s <= steps; ++s) last = solver.advance_to(depth * s / steps);
    ASSERT_TRUE(last.converged) << last.reason;
    ASSERT_FALSE(last.iterations.empty());
    start_residual.push_back(last.iterations.front().residual_norm);
  }
  const double order = std::log2(start_residual[0] / start_residual[1]);
  EXPECT_GT(order, 2.5) << "residuals " << start_residual[0] << " and " << start_residual[1] << " N";
}

TEST(FlatPunch, SurfaceContactMatchesTheTipNodeRuleForAFlatTip) {
  // Frictionless contact against the cylinder's actual surface mesh gives the §3.4 rule's force and pressure. The
  // punch is 5% wider than the mesh's ring of nodes at r = a so that no node sits exactly on the punch's rim (a node
  // on the rim can slide around the corner under node-to-surface contact).
  SolverOptions tip, surface;
  surface.contact = ContactModel::Surface;
  const auto a = punch(10, 3, 0.4, 0.01 * kA, tip, 1, 1.05), b = punch(10, 3, 0.4, 0.01 * kA, surface, 1, 1.05);
  ASSERT_TRUE(a.result.converged && b.result.converged) << b.result.reason;
  EXPECT_NEAR(b.force / a.force, 1.0, 0.02);
  // The node count is not asserted: a node within round-off of the punch's plane can flip in or out of contact
  // (15 vs 16 nodes seen) without changing the force.
  EXPECT_NEAR(b.result.contact_area[0] / a.result.contact_area[0], 1.0, 0.15);
  EXPECT_LT(b.result.max_penetration, 1e-2 * 0.01 * kA);
  EXPECT_NEAR(b.result.mean_contact_pressure[0] / a.result.mean_contact_pressure[0], 1.0, 0.1);
}

TEST(FlatPunch, RoundedEdgesApproachTheSharpPunchAndCarryLess) {
  // Surface contact with the punch's edge rounded (Indenter::edge_radius): as the radius goes to zero the force goes
  // to the sharp punch's; a radius of the order of the depth leaves part of the rim out of contact and carries less.
  SolverOptions surface;
  surface.contact = ContactModel::Surface;
  const double depth = 0.02 * kA;
  const auto sharp = punch(10, 3, 0.4, depth, surface, 1, 1.05);
  const auto fine = punch(10, 3, 0.4, depth, surface, 1, 1.05, 0.2e-6);
  const auto round = punch(10, 3, 0.4, depth, surface, 1, 1.05, 10e-6);
  ASSERT_TRUE(sharp.result.converged && fine.result.converged && round.result.converged)
      << fine.result.reason << round.result.reason;
  EXPECT_NEAR(fine.force / sharp.force, 1.0, 0.01);
  EXPECT_LT(round.force, 0.99 * fine.force);
  EXPECT_GT(round.force, 0.5 * sharp.force);
  EXPECT_LT(round.result.max_penetration, 1e-2 * depth);
}

}  // namespace

namespace {

TEST(FlatPunch, TipNodeRuleCountsTheNodesOnTheTipsEdge) {
  // The structured mesh's round core puts a ring of nodes exactly on r = a. The needle's mesh is the inscribed
  // 256-gon of its circle, and those nodes lie outside it between its vertices; the tip-node rule uses the true
  // outline (the circle through the polygon's vertices), so they are under the tip: the same nodes, and so the same
  // force, as a punch 0.1 % wider, whose polygon contains them.
  const auto exact = punch(10, 3, 0.4, 0.01 * kA, {}, 1, 1.0);
  const auto wider = punch(10, 3, 0.4, 0.01 * kA, {}, 1, 1.001);
  ASSERT_TRUE(exact.result.converged && wider.result.converged);
  EXPECT_EQ(exact.result.contact_nodes[0], wider.result.contact_nodes[0]);
  EXPECT_NEAR(exact.force / wider.force, 1.0, 1e-6);
  // A punch 1 % narrower leaves the ring out and carries less.
  const auto narrower = punch(10, 3, 0.4, 0.01 * kA, {}, 1, 0.99);
  EXPECT_LT(narrower.result.contact_nodes[0], exact.result.contact_nodes[0]);
  EXPECT_LT(narrower.force, 0.95 * exact.force);
}

}  // namespace

namespace {

TEST(FlatPunch, SameForcesWithOneAndTwoThreads) {
  // Assembly sums per fixed block and the sparse product over a fixed number of column ranges, so the run does not
  // depend on the number of threads: bitwise the same forces and energies (neo-Hookean, tip nodes, 4 steps to 20 %
  // of the radius).
  SolverOptions one, two;
  one.law = two.law = MaterialLaw::NeoHookean;
  one.threads = 1;
  two.threads = 2;
  const auto a = punch(10, 2, 0.4, 0.2 * kA, one, 4), b = punch(10, 2, 0.4, 0.2 * kA, two, 4);
  ASSERT_TRUE(a.result.converged && b.result.converged) << a.result.reason << b.result.reason;
  EXPECT_EQ(a.force, b.force);
  EXPECT_EQ(a.result.strain_energy, b.result.strain_energy);
  EXPECT_EQ(a.newton_iterations, b.newton_iterations);
}

// Leaves the allocator's free lists full of blocks of junk bytes (NaNs), so that memory the next run allocates
// and reads before writing shows up as a different result.
void fill_freed_heap_with_junk() {
  std::vector<std::unique_ptr<unsigned char[]>> blocks;
  for (int k = 0; k < 100000; ++k) {
    const std::size_t size = 16 + 16 * static_cast<std::size_t>(k % 8);
    blocks.emplace_back(new unsigned char[size]);
    std::memset(blocks.back().get(), 0xff, size);
  }
}

TEST(FlatPunch, SurfaceContactSameForcesWithOneAndTwoThreadsAndOnEveryRun) {
  // The same for surface contact, and on every run in one process: the needle's edge pseudo-normals were once summed
  // into uninitialised vectors, so a run's contact set, and its force (0.99 or 1.90 mN here), depended on what the
  // heap held before. The later runs start on a heap of freed junk, which made that defect fail this test.
  SolverOptions one, two;
  one.law = two.law = MaterialLaw::NeoHookean;
  one.contact = two.contact = ContactModel::Surface;
  one.threads = 1;
  two.threads = 2;
  const auto first = punch(10, 2, 0.4, 0.2 * kA, one, 4);
  ASSERT_TRUE(first.result.converged) << first.result.reason;
  fill_freed_heap_with_junk();
  for (int run = 0; run < 2; ++run) {
    const auto a = punch(10, 2, 0.4, 0.2 * kA, two, 4), b = punch(10, 2, 0.4, 0.2 * kA, one, 4);
    ASSERT_TRUE(a.result.converged && b.result.converged) << a.result.reason << b.result.reason;
    EXPECT_EQ(a.force, first.force) << "run " << run;
    EXPECT_EQ(b.force, first.force) << "run " << run;
    EXPECT_EQ(a.result.strain_energy, first.result.strain_energy) << "run " << run;
    EXPECT_EQ(a.newton_iterations, first.newton_iterations) << "run " << run;
  }
}

}  // namespace

namespace {

// Solvers at once (the calibration runs its FE side by side): every Cholesky solve sets OpenBLAS's process-wide
// thread count to one and back. Each solver saving and restoring it for itself let one save the other's "one" and
// leave the process at one thread for good (this test failed in 1 of 3 runs of 4 rounds then).
TEST(FlatPunch, SolversAtOnceLeaveTheBlasThreadCountAsItWas) {
  using Set = void (*)(int);
  using Get = int (*)();
  const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  ASSERT_TRUE(set && get) << "the FE links OpenBLAS (scripts/install-deps)";
  const int before = get();
  set(2);
  SolverOptions direct;
  direct.linear_solver = LinearSolver::Cholesky;  // a factorization and a solve per Newton iteration
  for (int round = 0; round < 8; ++round) {
    tbb::parallel_invoke([&] { punch(10, 2, 0.3, 0.01 * kA, direct, 3); },
                         [&] { punch(10, 2, 0.3, 0.01 * kA, direct, 3); });
    EXPECT_EQ(get(), 2) << "round " << round;
  }
  set(before);
}

}  // namespace
