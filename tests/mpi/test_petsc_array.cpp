// The PETSc backend's distributed assembly on a needle array (docs/fem_solver.md, "PETSc backend"): a 2 x 2 array of
// flat punches pressed into a nearly incompressible block (the nodal-averaged tetrahedron) gives every needle the
// built-in backend's force to 1e-6 on 1 and 2 ranks, each rank assembling only its own elements; and a step that
// fails ends on every rank with the built-in backend's status. Run on one process and under mpirun -np 2
// (tests/CMakeLists.txt); every rank runs both backends and checks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "needlekit/fem/parallel_session.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/io/indentation_case.hpp"

namespace needlekit {
namespace {

// 100 um punches at a 300 um pitch on a 400 um gel block (their rims embedded: every tip sees the same nodes),
// coarse: a few thousand tetrahedra.
constexpr const char* kCase = R"(name = "array_2x2"
[needle]
shape = "cylinder"
tip_diameter = "100 um"
length = "500 um"
[array]
rows = 2
columns = 2
pitch = "300 um"
margin = "250 um"
[tissue]
height = "400 um"
[[tissue.layers]]
name = "gel"
thickness = "rest"
youngs_modulus = "0.2 MPa"
poisson_ratio = 0.49
[mesh]
size_at_tip = "25 um"
size_far = "200 um"
refinement_radius = "60 um"
site_circle_radius = "50 um"
[loading]
depth = "24 um"
steps = 3
[model]
law = "neo-hookean"
contact = "tip-nodes"
)";

insertion::IndentationResult run(fem::SolverBackend backend, int max_iterations = 0) {
  insertion::IndentationCase c = io::parse_indentation_case_toml(kCase, "case.toml");
  c.solver.backend = backend;
  c.solver.threads = 1;                 // two ranks share this machine's cores
  c.solver.residual_tolerance = 1e-9;   // both backends converge far below the compared digits
  c.solver.max_iterations = max_iterations;
  if (max_iterations > 0) c.solver.max_cutbacks = 0;
  return insertion::run_indentation(c);
}

TEST(PetscArray, EveryNeedleGetsTheBuiltInForce) {
  const insertion::IndentationResult builtin = run(fem::SolverBackend::Builtin);
  const insertion::IndentationResult petsc = run(fem::SolverBackend::Petsc);
  ASSERT_EQ(builtin.status, insertion::IndentationStatus::ReachedDepth) << builtin.reason;
  ASSERT_EQ(petsc.status, builtin.status) << petsc.reason;
  ASSERT_EQ(petsc.needles.size(), 4u);
  ASSERT_EQ(petsc.steps.size(), 3u);
  for (size_t k = 0; k < petsc.needles.size(); ++k)
    for (size_t step = 0; step < petsc.steps.size(); ++step) {
      const double expected = builtin.needles[k].force[step];
      EXPECT_GT(expected, 0);
      EXPECT_NEAR(petsc.needles[k].force[step], expected, 1e-6 * expected)
          << "needle " << k << ", step " << step + 1 << " on " << fem::process_count() << " rank(s)";
    }
}

TEST(PetscArray, AFailedStepIsTheSameFailureOnEveryRank) {
  // One Newton iteration per step and no cut-back: the first step cannot converge. Every rank must stop there with
  // the built-in backend's status (a rank that went on would wait for the others forever: CTest's timeout).
  const insertion::IndentationResult builtin = run(fem::SolverBackend::Builtin, 1);
  const insertion::IndentationResult petsc = run(fem::SolverBackend::Petsc, 1);
  ASSERT_EQ(builtin.status, insertion::IndentationStatus::SolverFailed);
  EXPECT_EQ(petsc.status, builtin.status) << petsc.reason;
  EXPECT_EQ(petsc.steps.size(), builtin.steps.size());
  EXPECT_NE(petsc.reason.find("did not converge"), std::string::npos) << petsc.reason;
}

}  // namespace
}  // namespace needlekit
