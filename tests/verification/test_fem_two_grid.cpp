// The two-grid solver (fem::LinearSolver::TwoGrid): the same converged states as a direct solve, on a split mesh
// (linear tetrahedra, coarse level = the mesh it was split from), on a mesh with an independent coarser mesh of the
// same block (mesh::interpolating_coarse_level) and for quadratic tetrahedra (coarse level = their corner nodes),
// and CG iterations that do not grow when the mesh is refined (the point of a multigrid method: the cost of a solve
// stays proportional to the mesh).
#include <gtest/gtest.h>

#include <cmath>

#include "fem_test_support.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/mesh/coarse_level.hpp"
#include "needlekit/mesh/uniform_refinement.hpp"

using namespace needlekit;
using namespace needlekit::fem;
using namespace needlekit::fem::test_support;

namespace {

constexpr double kA = 115e-6;  // m, punch radius
constexpr double kE = 0.2e6;   // Pa

struct IndentRun {
  StepResult last;
  int newton_iterations = 0;
  int linear_iterations = 0;
  int factorizations = 0;
  LinearSolver solver = LinearSolver::Automatic;
};

IndentRun punch(const mesh::TetMesh& mesh, const mesh::CoarseLevel* coarse, SolverOptions o, double depth, int steps) {
  o.boundary = BoundaryCondition::QuarterSymmetry;
  const double corner = -5 * kA;  // quarter_punch_block(kA, 10 kA, ...): axis at the corner
  QuasiStaticSolver solver(mesh, {{placed_needle(flat_cylinder(kA, 300e-6), corner, corner, 0, 256), {0, 0, -1}}}, o,
                           coarse);
  IndentRun run;
  run.solver = solver.linear_solver();
  for (int s = 1; s <= steps; ++s) {
    run.last = solver.advance_to(depth * s / steps);
    if (!run.last.converged) break;
    run.newton_iterations += run.last.newton_iterations;
    run.factorizations += run.last.factorizations;
    for (const auto& it : run.last.iterations) run.linear_iterations += it.linear_iterations;
  }
  return run;
}

}  // namespace

TEST(TwoGrid, SameAnswerAsTheDirectSolveOnASplitMesh) {
  // Neo-Hookean to 30 % of the radius in 6 steps on a split quarter block.
  const auto split = mesh::refine_uniformly(quarter_punch_block(kA, 10 * kA, 2, kE, 0.4));
  SolverOptions direct, two_grid;
  direct.law = two_grid.law = MaterialLaw::NeoHookean;
  direct.linear_solver = LinearSolver::Cholesky;
  const IndentRun a = punch(split.mesh, &split.coarse, two_grid, 0.3 * kA, 6);
  const IndentRun b = punch(split.mesh, &split.coarse, direct, 0.3 * kA, 6);
  ASSERT_TRUE(a.last.converged && b.last.converged) << a.last.reason << b.last.reason;
  EXPECT_EQ(a.solver, LinearSolver::TwoGrid);  // Automatic picks it when a coarse level is given
  EXPECT_EQ(b.solver, LinearSolver::Cholesky);
  EXPECT_NEAR(a.last.indenter_force[0] / b.last.indenter_force[0], 1.0, 1e-5);
  EXPECT_NEAR(a.last.strain_energy / b.last.strain_energy, 1.0, 1e-5);
  EXPECT_GT(a.linear_iterations, 0);
  EXPECT_LT(a.factorizations, a.newton_iterations);  // the coarse operator is reused across solves
}

namespace {

// The quarter block with 4 core cells under the punch, its coarse level the same block with 2 (no fine node needs to
// be a coarse one), neo-Hookean to 30 % of the radius in 6 steps: the two-grid solve against the direct one. Returns
// the CG iterations per Newton solve.
double non_nested_against_direct(double nu) {
  const mesh::TetMesh fine = quarter_punch_block(kA, 10 * kA, 4, kE, nu);
  const mesh::CoarseLevel coarse = mesh::interpolating_coarse_level(fine, quarter_punch_block(kA, 10 * kA, 2, kE, nu));
  SolverOptions direct, two_grid;
  direct.law = two_grid.law = MaterialLaw::NeoHookean;
  direct.linear_solver = LinearSolver::Cholesky;
  const IndentRun a = punch(fine, &coarse, two_grid, 0.3 * kA, 6);
  const IndentRun b = punch(fine, nullptr, direct, 0.3 * kA, 6);
  EXPECT_TRUE(a.last.converged && b.last.converged) << a.last.reason << b.last.reason;
  EXPECT_EQ(a.solver, LinearSolver::TwoGrid);
  EXPECT_NEAR(a.last.indenter_force[0] / b.last.indenter_force[0], 1.0, 1e-5);
  EXPECT_NEAR(a.last.strain_energy / b.last.strain_energy, 1.0, 1e-5);
  return static_cast<double>(a.linear_iterations) / a.newton_iterations;
}

// CG iterations per Newton solve for a small indentation (5 % of the radius in 2 steps) of the quarter block with
// `core` cells under the punch, on the independent mesh of half as many, one coarse operator per run (the
// iterations measure the cycle alone).
double non_nested_iterations_per_solve(int core, double nu) {
  SolverOptions o;
  o.law = MaterialLaw::NeoHookean;
  o.two_grid_refresh_iterations = 1000;
  const mesh::TetMesh fine = quarter_punch_block(kA, 10 * kA, core, kE, nu);
  const mesh::CoarseLevel coarse =
      mesh::interpolating_coarse_level(fine, quarter_punch_block(kA, 10 * kA, core / 2, kE, nu));
  const IndentRun run = punch(fine, &coarse, o, 0.05 * kA, 2);
  EXPECT_TRUE(run.last.converged) << run.last.reason;
  return static_cast<double>(run.linear_iterations) / run.newton_iterations;
}

}  // namespace

TEST(TwoGrid, SameAnswerAsTheDirectSolveWithANonNestedCoarseMesh) {
  const double per_solve = non_nested_against_direct(0.4);
  // A coarse space that misses the fine one's smooth modes would need hundreds of iterations per solve.
  RecordProperty("iterations_per_solve", std::to_string(per_solve));
  EXPECT_LT(per_solve, 25.0);
}

TEST(TwoGrid, NonNestedIterationsDoNotGrowUnderRefinement) {
  // Fine meshes of 4 and 8 core cells, each on the independent mesh of half as many: the unknowns grow about
  // eightfold, the CG iterations per Newton solve stay put.
  const double coarse = non_nested_iterations_per_solve(4, 0.4), fine = non_nested_iterations_per_solve(8, 0.4);
  RecordProperty("iterations_per_solve", std::to_string(coarse) + " -> " + std::to_string(fine));
  EXPECT_LT(fine, 1.5 * coarse) << coarse << " -> " << fine << " iterations per solve";
}

TEST(TwoGrid, QuadraticTetrahedraUseTheirCornersAsTheCoarseLevel) {
  const auto mesh = quarter_punch_block(kA, 10 * kA, 2, kE, 0.45);
  SolverOptions direct, two_grid;
  direct.order = two_grid.order = ElementOrder::Quadratic;
  direct.linear_solver = LinearSolver::Cholesky;
  two_grid.linear_solver = LinearSolver::TwoGrid;
  const IndentRun a = punch(mesh, nullptr, two_grid, 0.1 * kA, 3);
  const IndentRun b = punch(mesh, nullptr, direct, 0.1 * kA, 3);
  ASSERT_TRUE(a.last.converged && b.last.converged) << a.last.reason << b.last.reason;
  EXPECT_EQ(a.solver, LinearSolver::TwoGrid);
  EXPECT_NEAR(a.last.indenter_force[0] / b.last.indenter_force[0], 1.0, 1e-5);
  EXPECT_NEAR(a.last.strain_energy / b.last.strain_energy, 1.0, 1e-5);
}

TEST(TwoGrid, IterationsDoNotGrowUnderRefinement) {
  // The same small indentation on a mesh split once and on that mesh split again (each with its parent as the
  // coarse level): the mesh width halves, the unknowns grow eightfold, the CG iterations per Newton iteration stay
  // put. (Diagonally preconditioned CG would need about twice as many per halving.)
  const auto once = mesh::refine_uniformly(quarter_punch_block(kA, 10 * kA, 2, kE, 0.4));
  const auto twice = mesh::refine_uniformly(once.mesh);
  SolverOptions o;
  o.law = MaterialLaw::NeoHookean;
  o.two_grid_refresh_iterations = 1000;  // one coarse operator per run: iterations measure the cycle alone
  const IndentRun a = punch(once.mesh, &once.coarse, o, 0.05 * kA, 2);
  const IndentRun b = punch(twice.mesh, &twice.coarse, o, 0.05 * kA, 2);
  ASSERT_TRUE(a.last.converged && b.last.converged) << a.last.reason << b.last.reason;
  const double per_solve_a = static_cast<double>(a.linear_iterations) / a.newton_iterations;
  const double per_solve_b = static_cast<double>(b.linear_iterations) / b.newton_iterations;
  EXPECT_LT(per_solve_b, 1.5 * per_solve_a) << per_solve_a << " -> " << per_solve_b << " iterations per solve";
  EXPECT_EQ(twice.mesh.tets.size(), 8 * once.mesh.tets.size());
}

// Nearly incompressible layers (ν >= 0.45: the nodal-averaged volume, whose tangent couples each node's patch): CG
// on K preconditioned by the Woodbury form of the displacement-pressure system with the two-grid cycle on the element
// part (nodal_volume_preconditioner.hpp). The same states as a direct solve, CG iterations that do not grow with the
// mesh and grow no faster than the square root of λ/μ as ν -> 1/2.
TEST(TwoGrid, NodalAverageSameAnswerAsTheDirectSolve) {
  const double per_solve = non_nested_against_direct(0.49);
  RecordProperty("iterations_per_solve", std::to_string(per_solve));
  EXPECT_LT(per_solve, 25.0);
}

TEST(TwoGrid, NodalAverageIterationsDoNotGrowWithTheMesh) {
  const auto per_solve = non_nested_iterations_per_solve;
  const double coarse_49 = per_solve(4, 0.49), fine_49 = per_solve(8, 0.49), fine_499 = per_solve(8, 0.499);
  RecordProperty("iterations_per_solve", std::to_string(coarse_49) + " -> " + std::to_string(fine_49) + ", at 0.499 " +
                                             std::to_string(fine_499));
  EXPECT_LT(fine_49, 1.5 * coarse_49) << coarse_49 << " -> " << fine_49 << " iterations per solve";
  // λ/μ grows tenfold from ν = 0.49 to 0.499. The diagonal Schur complement is an upper bound, not spectrally
  // equivalent: the iterations follow the square root of λ/μ (measured 12 -> 36 per solve; the two-grid cycle on A
  // alone, without the Woodbury term, took 21 -> 62, and the split Cholesky preconditioner's spectrum [μ/(λ+μ), 1]
  // has the same law). The bound catches a preconditioner whose iterations grow like λ/μ itself.
  EXPECT_LT(fine_499, 1.2 * std::sqrt(10.0) * fine_49) << "ν = 0.49: " << fine_49 << ", 0.499: " << fine_499;
}

TEST(TwoGrid, NodalAverageSameForcesWithOneAndTwoThreads) {
  // The patch products write each node's and each dof's entry from one task, the Galerkin product each coarse
  // column from one task: bitwise the same run whatever the number of threads.
  const mesh::TetMesh fine = quarter_punch_block(kA, 10 * kA, 4, kE, 0.49);
  const mesh::CoarseLevel coarse = mesh::interpolating_coarse_level(fine, quarter_punch_block(kA, 10 * kA, 2, kE, 0.49));
  SolverOptions one, two;
  one.law = two.law = MaterialLaw::NeoHookean;
  one.threads = 1;
  two.threads = 2;
  const IndentRun a = punch(fine, &coarse, one, 0.2 * kA, 4), b = punch(fine, &coarse, two, 0.2 * kA, 4);
  ASSERT_TRUE(a.last.converged && b.last.converged) << a.last.reason << b.last.reason;
  EXPECT_EQ(a.solver, LinearSolver::TwoGrid);
  EXPECT_EQ(a.last.indenter_force[0], b.last.indenter_force[0]);
  EXPECT_EQ(a.last.strain_energy, b.last.strain_energy);
  EXPECT_EQ(a.linear_iterations, b.linear_iterations);
}

TEST(TwoGrid, NeedsACoarseLevelForLinearElements) {
  const auto mesh = quarter_punch_block(kA, 10 * kA, 2, kE, 0.4);
  SolverOptions o;
  o.boundary = BoundaryCondition::QuarterSymmetry;
  o.linear_solver = LinearSolver::TwoGrid;
  try {
    QuasiStaticSolver solver(mesh, {{placed_needle(flat_cylinder(kA, 300e-6), -5 * kA, -5 * kA, 0, 64), {0, 0, -1}}}, o);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("coarse level"), std::string::npos) << e.what();
  }
}
