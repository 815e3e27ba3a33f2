// The PETSc backend (docs/fem_solver.md, "PETSc backend") against the built-in one: the same load steps give the same
// needle forces to 1e-6 in the same Newton iterations (an operator that were not the tangent K, such as the shell of
// the nodal average's patch term with a term missing, would still converge, but in more of them). tests/CMakeLists.txt runs this executable on one process and under mpirun -np 2; on two
// ranks every rank runs both backends (the Newton loop is replicated) and checks.
#include <gtest/gtest.h>

#include <vector>

#include "../verification/fem_test_support.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/fem/parallel_session.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

namespace needlekit::fem {
namespace {

constexpr double kA = 100e-6;   // m, punch radius
constexpr double kE = 10e3;     // Pa

struct PunchRun {
  std::vector<double> forces;        // N, per step
  std::vector<int> newton_iterations;  // per step
  std::vector<double> volume_ratios;   // per step: the most compressed tetrahedron's J
};

// A quarter flat punch pressed to 10 % of its radius in two steps.
PunchRun punch(SolverOptions options, double poisson_ratio) {
  const auto mesh = test_support::quarter_punch_block(kA, 10 * kA, 2, kE, poisson_ratio);
  options.boundary = BoundaryCondition::QuarterSymmetry;
  options.threads = 1;  // two ranks share this machine's cores
  options.residual_tolerance = 1e-9;  // both backends converge far below the compared digits
  const auto needle = test_support::placed_needle(test_support::flat_cylinder(kA, 300e-6), -5 * kA, -5 * kA, 0, 64);
  QuasiStaticSolver solver(mesh, {{needle, {0, 0, -1}}}, options);
  PunchRun run;
  for (const double depth : {0.05 * kA, 0.1 * kA}) {
    const StepResult step = solver.advance_to(depth);
    EXPECT_TRUE(step.converged) << step.reason;
    run.forces.push_back(step.indenter_force[0]);
    run.newton_iterations.push_back(step.newton_iterations);
    run.volume_ratios.push_back(step.min_volume_ratio);
  }
  return run;
}

void expect_same_forces(const SolverOptions& options, double poisson_ratio) {
  SolverOptions petsc = options;
  petsc.backend = SolverBackend::Petsc;
  const PunchRun builtin = punch(options, poisson_ratio);
  const PunchRun with_petsc = punch(petsc, poisson_ratio);
  ASSERT_EQ(builtin.forces.size(), with_petsc.forces.size());
  for (size_t k = 0; k < builtin.forces.size(); ++k) {
    EXPECT_GT(builtin.forces[k], 0);
    EXPECT_NEAR(with_petsc.forces[k], builtin.forces[k], 1e-6 * builtin.forces[k])
        << "step " << k << " on " << process_count() << " rank(s)";
    EXPECT_EQ(with_petsc.newton_iterations[k], builtin.newton_iterations[k])
        << "step " << k << " on " << process_count() << " rank(s)";
    // Every rank holds the whole displacement, so each measures the whole mesh's most compressed tetrahedron.
    EXPECT_LT(builtin.volume_ratios[k], 1.0);
    EXPECT_NEAR(with_petsc.volume_ratios[k], builtin.volume_ratios[k], 1e-9)
        << "step " << k << " on " << process_count() << " rank(s)";
  }
}

TEST(PetscBackend, GivesTheBuiltInForcesWithLinearElements) {
  expect_same_forces(SolverOptions{}, 0.4);  // St Venant-Kirchhoff
}

TEST(PetscBackend, GivesTheBuiltInForcesWithTheNodalAveragedVolume) {
  SolverOptions options;  // neo-Hookean at nu = 0.49: the nodal average's two-ring tangent
  options.law = MaterialLaw::NeoHookean;
  expect_same_forces(options, 0.49);
}

// A 230 um flat punch 40 um into a coarse silicone block under surface contact, rezoned after its first step.
insertion::IndentationResult rezoned_punch(SolverBackend backend) {
  insertion::IndentationCase c;
  const needle::NeedleGeometry cylinder{needle::Shape::Cylinder, 230e-6, 230e-6, 0, 1000e-6};
  c.geometry = cylinder;
  c.needle = needle::needle_surface_mesh(cylinder, {24, 4});
  c.block.width = c.block.length = 2000e-6;
  c.block.layers = {{"silicone rubber", 1000e-6, 0.2e6, 0.49}};
  c.block.size_at_site = 60e-6;
  c.block.refinement_radius = 200e-6;
  c.block.size_far = 600e-6;
  c.block.threads = 1;
  c.depth = 40e-6;
  c.steps = 2;
  c.solver.law = MaterialLaw::NeoHookean;
  c.solver.contact = ContactModel::Surface;
  c.solver.backend = backend;
  c.solver.threads = 1;
  c.solver.residual_tolerance = 1e-9;
  c.solver.rezone = true;
  c.solver.rezone_volume_ratio = 0.999;  // after the first step
  c.solver.max_remeshes = 1;
  return insertion::run_indentation(c);
}

TEST(PetscBackend, RezonesAsTheBuiltInBackendOnEveryRank) {
  // Every rank meshes the crushed region anew on its own (Gmsh's Delaunay on one thread is deterministic): the ranks'
  // meshes must be the same, or the distributed solve would not be the built-in one's.
  const insertion::IndentationResult builtin = rezoned_punch(SolverBackend::Builtin);
  const insertion::IndentationResult petsc = rezoned_punch(SolverBackend::Petsc);
  ASSERT_EQ(petsc.status, insertion::IndentationStatus::ReachedDepth) << petsc.reason;
  ASSERT_EQ(builtin.remeshes.size(), 1u);
  ASSERT_EQ(petsc.remeshes.size(), 1u);
  EXPECT_TRUE(petsc.remeshes[0].failure.empty()) << petsc.remeshes[0].failure;
  EXPECT_EQ(petsc.remeshes[0].elements_after, builtin.remeshes[0].elements_after);
  EXPECT_NEAR(petsc.remeshes[0].force_after, builtin.remeshes[0].force_after, 1e-6 * builtin.remeshes[0].force_after);
  ASSERT_EQ(petsc.steps.size(), 2u);
  EXPECT_NEAR(petsc.steps[1].force, builtin.steps[1].force, 1e-6 * builtin.steps[1].force)
      << "on " << process_count() << " rank(s)";
}

TEST(PetscBackend, IsCompiledIn) {
  EXPECT_TRUE(backend_compiled(SolverBackend::Petsc));
  EXPECT_EQ(compiled_backend_names(), "builtin, petsc");
}

}  // namespace
}  // namespace needlekit::fem

int main(int argc, char** argv) {
  needlekit::fem::ParallelSession session(argc, argv);  // MPI first under mpirun
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
