// The patch pipeline's progress callback (patch::FitAndEvaluateOptions::progress): fractions in [0, 1] that never
// decrease, from 0 to 1, one report per node mapped by node sweeping and per Newton iteration of the equilibrium fit
// inside the fit's share; the callback changes nothing in the result; returning false stops the run at once with
// needlekit::Interrupted.
#include <gtest/gtest.h>

#include <vector>

#include "../support/analytic_surfaces.hpp"
#include "../support/patch_designs.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/patch/fit_and_evaluate.hpp"

namespace needlekit::patch {
namespace {

PatchDesignOptions design_options(int n, double width) { return test::su8_cylinder_patch(width, n); }

// The cylinder of radius 20 mm about X, top line at z = r.
geometry::SurfaceMesh cylinder() {
  geometry::TriangleMesh mesh = test::open_cylinder_mesh(0.02, 0.04, 256, 16);
  for (auto& v : mesh.vertices) v = Eigen::Vector3d(v.z() - 0.02, v.x(), v.y());
  return geometry::SurfaceMesh(mesh);
}

FitAndEvaluateOptions on_top(PatchKind kind) {
  FitAndEvaluateOptions o;
  o.placement.center = {0, 0, 0.02};
  o.fit.kind = kind;
  o.fit.flexible.max_spring_energy = 1e-3;
  return o;
}

struct Reports {
  std::vector<double> fractions;
  int inside_fit() const {
    int n = 0;
    for (double f : fractions) n += f > FitAndEvaluateOptions::kFrameShare && f < FitAndEvaluateOptions::kFitEnd - 1e-12;
    return n;
  }
};

void expect_monotone_from_0_to_1(const std::vector<double>& f) {
  ASSERT_GE(f.size(), 3u);
  EXPECT_EQ(f.front(), 0);
  EXPECT_EQ(f.back(), 1);
  for (std::size_t i = 1; i < f.size(); ++i) EXPECT_GE(f[i], f[i - 1]) << "report " << i;
}

TEST(PatchProgress, NodeSweepingReportsEveryNodeMappedAndChangesNothing) {
  const geometry::SurfaceMesh surface = cylinder();
  const PatchDesignOptions design = design_options(8, 8e-3);
  const FitAndEvaluateResult quiet = fit_and_evaluate(surface, design, on_top(PatchKind::Flexible));
  Reports reports;
  FitAndEvaluateOptions options = on_top(PatchKind::Flexible);
  options.progress = [&](double f) { reports.fractions.push_back(f); return true; };
  const FitAndEvaluateResult r = fit_and_evaluate(surface, design, options);
  ASSERT_EQ(r.status, FitStatus::Ok) << r.reason;
  expect_monotone_from_0_to_1(reports.fractions);
  // 63 nodes mapped after the first one, the last at the end of the fit's share: 62 inside it.
  EXPECT_EQ(reports.inside_fit(), 62);
  EXPECT_EQ(r.fit.positions, quiet.fit.positions);
  EXPECT_EQ(r.evaluation.penetrating, quiet.evaluation.penetrating);
}

TEST(PatchProgress, TheEquilibriumFitReportsItsNewtonIterationsAndReachesOneWhenConverged) {
  const geometry::SurfaceMesh surface = cylinder();
  Reports reports;
  FitAndEvaluateOptions options = on_top(PatchKind::Equilibrium);
  options.spring_geodesics = true;
  options.progress = [&](double f) { reports.fractions.push_back(f); return true; };
  const FitAndEvaluateResult r = fit_and_evaluate(surface, design_options(8, 8e-3), options);
  ASSERT_EQ(r.status, FitStatus::Ok) << r.reason;
  expect_monotone_from_0_to_1(reports.fractions);
  ASSERT_GT(r.fit.iterations, 1);
  // One report per iteration and one for the converged iterate (at the fit's end), and the five stages around them:
  // start, frame, fit, evaluation, springs along the surface. Iteration k is at least k / max_iterations of the fit:
  // iteration 0 at its start, the converged iterate at its end, the others inside.
  EXPECT_EQ(reports.inside_fit(), r.fit.iterations - 1);
  const double fit_share = FitAndEvaluateOptions::kFitEnd - FitAndEvaluateOptions::kFrameShare;
  EXPECT_GE(reports.fractions[2 + r.fit.iterations - 1],
            FitAndEvaluateOptions::kFrameShare + fit_share * (r.fit.iterations - 1) / 500.0 - 1e-12);
  EXPECT_EQ(reports.fractions.size(), static_cast<std::size_t>(r.fit.iterations) + 1 + 5);
  EXPECT_EQ(reports.fractions[reports.fractions.size() - 2], FitAndEvaluateOptions::kEvaluationEnd);
}

TEST(PatchProgress, FalseStopsTheFitAtOnce) {
  const geometry::SurfaceMesh surface = cylinder();
  for (const PatchKind kind : {PatchKind::Flexible, PatchKind::Equilibrium, PatchKind::Rigid}) {
    int calls = 0;
    FitAndEvaluateOptions options = on_top(kind);
    options.progress = [&](double) { return ++calls < 3; };
    EXPECT_THROW(fit_and_evaluate(surface, design_options(8, 8e-3), options), Interrupted) << to_string(kind);
    EXPECT_EQ(calls, 3) << to_string(kind);
  }
}

}  // namespace
}  // namespace needlekit::patch
