// patch::fit_and_evaluate, the pipeline behind `needlekit patch` and `reproduce` §6.4 (design -> frame -> fit ->
// evaluate), on analytic surfaces:
//  - on a plane every needle of a rigid patch stands normal to the surface, travels its full length and has the
//    index of the single straight needle (PatchEvaluation::reference), and the springs keep their rest lengths along
//    the surface;
//  - on a cylinder of radius r (generators along X) the rigid patch's needle at lateral offset y meets the surface
//    at the angle asin(|y| / r), so its buckling and bending forces are |F(A)|/cos and |F(A)| tan of that angle
//    (Eqs 5.3, 5.4);
//  - a patch larger than the surface is a status with a reason, not an exception.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/analytic_surfaces.hpp"
#include "../support/patch_designs.hpp"
#include "needlekit/patch/fit_and_evaluate.hpp"

namespace needlekit::patch {
namespace {

PatchDesignOptions design_options(double width, int n) { return test::su8_cylinder_patch(width, n); }

FitAndEvaluateOptions rigid_at(const Eigen::Vector3d& center, bool geodesics = false) {
  FitAndEvaluateOptions o;
  o.placement.center = center;
  o.fit.kind = PatchKind::Rigid;
  o.spring_geodesics = geodesics;
  return o;
}

TEST(FitAndEvaluate, RigidPatchOnAPlaneHasEveryNeedleStraightAndFullyInserted) {
  const geometry::SurfaceMesh plane(test::plane_grid_mesh(0.02, 37));
  const FitAndEvaluateResult r =
      fit_and_evaluate(plane, design_options(10e-3, 10), rigid_at({0.0013, -0.0021, 0}, true));
  ASSERT_EQ(r.status, FitStatus::Ok) << r.reason;
  EXPECT_TRUE(r.reason.empty());
  EXPECT_EQ(r.design.node_count(), 100);
  EXPECT_NEAR((r.frame.surface_point - Eigen::Vector3d(0.0013, -0.0021, 0)).norm(), 0, 1e-12);
  const PatchEvaluation& e = r.evaluation;
  EXPECT_EQ(e.on_surface, 100);
  EXPECT_EQ(e.penetrating, 100);
  EXPECT_NEAR(e.angle.max, 0, 1e-9);
  EXPECT_NEAR(e.travel.min, 400e-6, 1e-12);
  EXPECT_NEAR(e.travel.max, 400e-6, 1e-12);
  const double f = std::abs(e.reference.puncture_force);
  EXPECT_NEAR(e.buckling_force.min, f, 1e-12 * f);
  EXPECT_NEAR(e.bending_force.max, 0, 1e-9 * f);
  ASSERT_GT(e.reference.performance_index, 0);
  EXPECT_NEAR(e.performance_index.min / e.reference.performance_index, 1, 1e-9);
  EXPECT_NEAR(e.performance_index.max / e.reference.performance_index, 1, 1e-9);
  ASSERT_TRUE(r.geodesics);
  EXPECT_EQ(r.geodesics->not_converged, 0);
  EXPECT_LT(r.geodesics->strain_abs.max, 1e-9);
  EXPECT_GE(r.fit_seconds, 0);
}

TEST(FitAndEvaluate, RigidPatchOnACylinderMeetsItAtTheAnglesOfTheCircle) {
  const double radius = 0.02;
  geometry::TriangleMesh mesh = test::open_cylinder_mesh(radius, 0.06, 720, 24);
  // The cylinder about X (generators along X, top line at z = r): (x, y, z) -> (z - 0.03, x, y).
  for (auto& v : mesh.vertices) v = Eigen::Vector3d(v.z() - 0.03, v.x(), v.y());
  const geometry::SurfaceMesh cylinder(mesh);
  const FitAndEvaluateResult r = fit_and_evaluate(cylinder, design_options(10e-3, 6), rigid_at({0, 0, radius}));
  ASSERT_EQ(r.status, FitStatus::Ok) << r.reason;
  const double f = std::abs(r.evaluation.reference.puncture_force);
  const double facet = M_PI / 720;  // half the angle between facet normals: the faceted normal's error
  int checked = 0;
  for (const NeedleState& needle : r.evaluation.needles) {
    if (!needle.hits_surface) continue;
    const double angle = std::asin(std::abs(needle.surface_point.y()) / radius);
    EXPECT_NEAR(needle.angle, angle, facet) << "needle at y = " << needle.surface_point.y();
    EXPECT_NEAR(needle.buckling_force, f / std::cos(needle.angle), 1e-12 * f);
    EXPECT_NEAR(needle.bending_force, f * std::tan(needle.angle), 1e-12 * f);
    ++checked;
  }
  EXPECT_EQ(checked, 36);
  EXPECT_GT(r.evaluation.angle.max, 0.2);  // the outer rows at |y| = 5 mm: asin(0.25) = 0.253 rad
}

TEST(FitAndEvaluate, PatchLargerThanTheSurfaceIsAStatus) {
  const geometry::SurfaceMesh small(test::plane_grid_mesh(0.003, 13));  // 6 x 6 mm under a 10 x 10 mm patch
  const FitAndEvaluateResult r = fit_and_evaluate(small, design_options(10e-3, 10), rigid_at({0, 0, 0}));
  EXPECT_NE(r.status, FitStatus::Ok);
  EXPECT_FALSE(r.reason.empty());
  EXPECT_EQ(r.evaluation.needles.size(), 100u);
  EXPECT_LT(r.evaluation.on_surface, 100);
  EXPECT_GT(r.evaluation.on_surface, 0);
}

}  // namespace
}  // namespace needlekit::patch
