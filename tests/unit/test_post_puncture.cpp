// Post-puncture model (§3.6): triangle classes of the needlekit needles, the load prism of Eqs 3.19-3.20, the depth
// sweep against the one-depth evaluation, scale invariance, the fit, the complete insertion curve and its bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "needlekit/core/errors.hpp"
#include "../support/expect_invalid.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/insertion/insertion_curve.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/insertion/triangle_classification.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

using namespace needlekit;
using namespace needlekit::insertion;
using testing::HasSubstr;
using needlekit::test::expect_invalid;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double um = 1e-6;

geometry::TriangleMesh needle_mesh(needle::Shape shape, double d1, double d2, double d3, double length, int n = 64,
                                   int axial = 16) {
  return needle::needle_surface_mesh({shape, d1, d2, d3, length}, {n, axial});
}

TEST(TriangleClassification, FlatCylinderHasOnlyAlphaTrianglesOnItsTip) {
  const auto mesh = needle_mesh(needle::Shape::Cylinder, 230 * um, 230 * um, 0, 1000 * um);
  const auto c = classify_triangles(mesh);
  EXPECT_TRUE(c.beta.empty());
  EXPECT_FALSE(c.alpha.empty());
  EXPECT_GT(c.side, 0);
  EXPECT_GT(c.back, 0);
  const double polygon = 0.5 * 64 * std::pow(115 * um, 2) * std::sin(2 * kPi / 64);
  EXPECT_NEAR(c.alpha_area / polygon, 1.0, 1e-12);
  for (int t : c.alpha) EXPECT_EQ(c.classes[static_cast<std::size_t>(t)], TriangleClass::Alpha);
}

TEST(TriangleClassification, ConeSlopeIsBetaAndBoreIsChannel) {
  const auto mesh = needle_mesh(needle::Shape::Cone, 60 * um, 230 * um, 20 * um, 500 * um);
  TriangleClassificationOptions options;
  options.bore_radius = 10 * um;
  const auto c = classify_triangles(mesh, options);
  EXPECT_EQ(c.beta.size(), 64u * 2 * 16);  // the slope: two triangles per quad
  EXPECT_GT(c.channel, 0);                 // the bore wall
  const double annulus = 0.5 * 64 * std::sin(2 * kPi / 64) * (std::pow(30 * um, 2) - std::pow(10 * um, 2));
  EXPECT_NEAR(c.alpha_area / annulus, 1.0, 1e-9);
  // The same bore found by visibility (rays along the normals hit the opposite wall) with the SurfaceMesh.
  const geometry::SurfaceMesh surface(mesh);
  const auto by_rays = classify_triangles(mesh, {}, &surface);
  EXPECT_EQ(by_rays.beta.size(), c.beta.size());
  EXPECT_EQ(by_rays.alpha.size(), c.alpha.size());
}

TEST(TriangleClassification, OcclusionHidesAFaceBehindAnOverhang) {
  // A C-shaped prism (profile in x, z extruded over y in [0, 1]): the foot's top face (z = 1, x in [1, 3]) faces
  // the insertion direction +z, but the rays from its vertices along +z hit the arm above it (z = 2): occluded.
  geometry::TriangleMesh mesh;
  const std::vector<Eigen::Vector2d> profile{{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {3, 2}, {3, 3}, {0, 3}};
  const int m = static_cast<int>(profile.size());
  for (double y : {0.0, 1.0})
    for (const auto& p : profile) mesh.vertices.emplace_back(p.x(), y, p.y());
  for (int i = 0; i < m; ++i) {
    const int a = i, b = (i + 1) % m;
    mesh.triangles.push_back({a, a + m, b + m});
    mesh.triangles.push_back({a, b + m, b});
  }
  // Caps: the C split into (0,1,2,3) foot+stem bottom, (0,3,4,7) stem, (7,4,5,6) arm.
  const std::vector<std::array<int, 4>> quads{{0, 1, 2, 3}, {0, 3, 4, 7}, {7, 4, 5, 6}};
  for (const auto& q : quads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
    mesh.triangles.push_back({q[0] + m, q[2] + m, q[1] + m});
    mesh.triangles.push_back({q[0] + m, q[3] + m, q[2] + m});
  }
  ASSERT_GT(geometry::signed_volume(mesh), 0);
  ASSERT_EQ(geometry::topology_report(mesh).boundary_edges, 0);
  const geometry::SurfaceMesh surface(mesh);
  TriangleClassificationOptions options;
  options.axis_point = {0.5, 0.5, 0};
  const auto plain = classify_triangles(mesh, options, &surface);
  EXPECT_EQ(plain.alpha.size(), 4u);  // the top z = 3 and the foot's top z = 1
  options.occlusion_test = true;
  const auto occluded = classify_triangles(mesh, options, &surface);
  EXPECT_EQ(occluded.alpha.size(), 2u);
  EXPECT_EQ(occluded.occluded, 2);
}

TEST(TriangleClassification, BadMeshesAreNamed) {
  auto mesh = needle_mesh(needle::Shape::Cone, 30 * um, 230 * um, 0, 500 * um, 16, 2);
  auto inverted = mesh;
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  expect_invalid([&] { classify_triangles(inverted); }, "inverted normals");
  auto open = mesh;
  open.triangles.pop_back();
  expect_invalid([&] { classify_triangles(open); }, "open");
  auto non_manifold = mesh;
  non_manifold.triangles.push_back(mesh.triangles.front());
  expect_invalid([&] { classify_triangles(non_manifold); }, "non-manifold");
  expect_invalid([&] { classify_triangles(geometry::TriangleMesh{}); }, "empty");
  TriangleClassificationOptions occlusion;
  occlusion.occlusion_test = true;
  expect_invalid([&] { classify_triangles(mesh, occlusion); }, "SurfaceMesh");

  // A knife edge of half-angle 0.25 deg: both flanks are within the 1 deg side tolerance: nothing faces d.
  geometry::TriangleMesh wedge;
  const double t = std::tan(0.25 * kPi / 180);
  wedge.vertices = {{-t, 0, 0}, {t, 0, 0}, {0, 0, 1}, {-t, 1, 0}, {t, 1, 0}, {0, 1, 1}};
  wedge.triangles = {{0, 1, 2}, {3, 5, 4}, {0, 4, 1}, {0, 3, 4}, {1, 4, 5}, {1, 5, 2}, {2, 5, 3}, {2, 3, 0}};
  const Eigen::Vector3d inside(0, 0.5, 0.3);
  for (auto& tri : wedge.triangles) {  // a convex solid: orient every face away from an interior point
    const auto& p = wedge.vertices;
    const Eigen::Vector3d n = (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]);
    if (n.dot(p[tri[0]] - inside) < 0) std::swap(tri[1], tri[2]);
  }
  ASSERT_GT(geometry::signed_volume(wedge), 0);
  expect_invalid([&] { classify_triangles(wedge); }, "no triangle faces the insertion direction");
}

TEST(PostPunctureForce, LoadPrismOfThreeTetrahedraIsAreaTimesMeanLoad) {  // Eqs 3.19-3.20
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1, 1), h(0, 2);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d p1(u(random), u(random), u(random)), p2(u(random), u(random), u(random)),
        p3(u(random), u(random), u(random));
    const double h1 = h(random), h2 = h(random), h3 = h(random);
    const double area = 0.5 * (p2 - p1).cross(p3 - p1).norm();
    EXPECT_NEAR(load_prism_volume(p1, p2, p3, h1, h2, h3), area * (h1 + h2 + h3) / 3, 1e-12);
  }
}

TEST(PostPunctureForce, DepthSweepEqualsOneDepthEvaluationAndIsMonotonic) {
  const auto mesh = needle_mesh(needle::Shape::Bevel, 120 * um, 230 * um, 90 * um, 1000 * um, 48, 12);
  const auto loads = post_puncture_loads(mesh);
  std::vector<double> depths;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(0, 1200 * um);
  for (int k = 0; k < 200; ++k) depths.push_back(u(random));
  depths.push_back(0);
  depths.push_back(1000 * um);
  const auto forces = post_puncture_forces(loads, depths, 0.2e6, 0.168);
  for (std::size_t k = 0; k < depths.size(); ++k)
    EXPECT_NEAR(forces[k], post_puncture_force(loads, depths[k], 0.2e6, 0.168), 1e-12 * (1 + forces[k]));
  std::vector<double> sorted = depths;
  std::sort(sorted.begin(), sorted.end());
  const auto ordered = post_puncture_forces(loads, sorted, 0.2e6, 0.168);
  for (std::size_t k = 1; k < ordered.size(); ++k) EXPECT_GE(ordered[k], ordered[k - 1] - 1e-15);
  EXPECT_EQ(ordered.front(), 0.0);
  // Beyond the needle's length, nothing more enters the tissue.
  EXPECT_NEAR(post_puncture_force(loads, 1100 * um, 1, 1), post_puncture_force(loads, 1000 * um, 1, 1), 1e-18);
}

TEST(PostPunctureForce, ForceScalesWithAreaFromMicrometresToMetres) {
  const auto small = needle_mesh(needle::Shape::Cone, 40 * um, 230 * um, 0, 600 * um, 32, 8);
  const auto large = needle_mesh(needle::Shape::Cone, 40, 230, 0, 600, 32, 8);
  const auto a = post_puncture_loads(small), b = post_puncture_loads(large);
  for (double h : {0.1, 0.3, 0.6}) {
    const double fa = post_puncture_load_area(a, h * 1000 * um), fb = post_puncture_load_area(b, h * 1000);
    EXPECT_NEAR(fb / fa, 1e12, 1e12 * 1e-9);
  }
}

TEST(PostPunctureForce, FitRecoversTheScaleAndRejectsBadCurves) {
  const auto mesh = needle_mesh(needle::Shape::Bevel, 10 * um, 230 * um, 0, 1000 * um, 32, 8);
  const auto loads = post_puncture_loads(mesh);
  ForceDepthCurve measured;
  for (int k = 1; k <= 20; ++k) {
    measured.depth.push_back(50 * um * k);
    measured.force.push_back(post_puncture_force(loads, measured.depth.back(), 0.2e6, 0.168));
  }
  PostPunctureFitOptions options;
  options.stiffness = 0.2e6;
  const auto fit = fit_post_puncture(loads, measured, options);
  EXPECT_NEAR(fit.scale, 0.168, 1e-12);
  EXPECT_LT(fit.relative_rms, 1e-12);
  options.fit_stiffness = true;
  options.scale = 0.336;
  EXPECT_NEAR(fit_post_puncture(loads, measured, options).stiffness, 0.1e6, 1e-3);

  auto shuffled = measured;
  std::swap(shuffled.depth[3], shuffled.depth[4]);
  expect_invalid([&] { fit_post_puncture(loads, shuffled); }, "depth is not monotonic");
  expect_invalid([&] { fit_post_puncture(loads, ForceDepthCurve{}); }, "no samples");
}

PrePunctureCurve quadratic_pre_curve(double puncture_depth, double puncture_force, bool punctures = true) {
  PrePunctureCurve pre;
  for (int k = 1; k <= 10; ++k) {
    const double x = puncture_depth * k / 10;
    pre.curve.depth.push_back(x);
    pre.curve.force.push_back(puncture_force * (x / puncture_depth) * (x / puncture_depth));
  }
  if (punctures) pre.puncture = PuncturePoint{puncture_depth, puncture_force, PunctureCriterion::CriticalPressure};
  return pre;
}

TEST(InsertionCurve, SingleNeedleJoinsIndentationAndCuttingWithTheRelaxationDrop) {
  const auto mesh = needle_mesh(needle::Shape::Bevel, 10 * um, 230 * um, 0, 1000 * um, 32, 8);
  const auto loads = post_puncture_loads(mesh);
  NeedleInsertion needle{quadratic_pre_curve(230 * um, 0.014), &loads, 0.2e6, 0.168, 0};
  InsertionCurveOptions options;
  options.final_depth = 1000 * um;
  options.cutting_samples = 50;
  const auto curve = insertion_curve({needle}, options);
  EXPECT_EQ(curve.status, InsertionStatus::Complete);
  ASSERT_EQ(curve.punctures.size(), 1u);
  const auto& event = curve.punctures.front();
  EXPECT_DOUBLE_EQ(event.displacement, 230 * um);
  EXPECT_DOUBLE_EQ(event.force_before, 0.014);
  EXPECT_NEAR(event.force_after, post_puncture_force(loads, 230 * um, 0.2e6, 0.168), 1e-15);
  EXPECT_NEAR(event.drop, 0.014 - event.force_after, 1e-15);
  // 1 (zero) + 10 pre samples (the last is the puncture) + the post sample at the puncture + 50 cutting samples.
  ASSERT_EQ(curve.depth.size(), 62u);
  EXPECT_EQ(curve.depth.front(), 0.0);
  EXPECT_DOUBLE_EQ(curve.depth.back(), 1000 * um);
  for (std::size_t s = 0; s < curve.depth.size(); ++s) {
    const bool cutting = s >= 11;
    EXPECT_EQ(curve.phase[s], cutting ? InsertionPhase::Cutting : InsertionPhase::Indentation) << s;
    if (cutting) EXPECT_NEAR(curve.force[s], post_puncture_force(loads, curve.depth[s], 0.2e6, 0.168), 1e-15);
  }
  EXPECT_DOUBLE_EQ(curve.depth[10], curve.depth[11]);
  EXPECT_DOUBLE_EQ(curve.force[10], 0.014);
}

TEST(InsertionCurve, ArrayForceIsTheSumOverNeedlesInTheirPhases) {
  const auto mesh = needle_mesh(needle::Shape::Cone, 40 * um, 230 * um, 0, 1000 * um, 32, 8);
  const auto loads = post_puncture_loads(mesh);
  NeedleInsertion first{quadratic_pre_curve(200 * um, 0.02), &loads, 0.2e6, 0.2, 0};
  NeedleInsertion second{quadratic_pre_curve(300 * um, 0.03), &loads, 0.2e6, 0.2, 50 * um};
  InsertionCurveOptions options;
  options.final_depth = 800 * um;
  const auto curve = insertion_curve({first, second}, options);
  ASSERT_EQ(curve.punctures.size(), 2u);
  EXPECT_DOUBLE_EQ(curve.punctures[0].displacement, 200 * um);
  EXPECT_DOUBLE_EQ(curve.punctures[1].displacement, 350 * um);
  for (std::size_t s = 0; s < curve.depth.size(); ++s) {
    const double u = curve.depth[s];
    if (u > 400 * um) {
      const double expected = post_puncture_force(loads, u, 0.2e6, 0.2) +
                              post_puncture_force(loads, u - 50 * um, 0.2e6, 0.2);
      EXPECT_NEAR(curve.force[s], expected, 1e-14);
      EXPECT_EQ(curve.punctured_needles[s], 2);
    }
    if (u > 200 * um && u < 340 * um) {
      const double x = (u - 50 * um) / (300 * um);
      EXPECT_NEAR(curve.force[s], post_puncture_force(loads, u, 0.2e6, 0.2) + 0.03 * x * x, 2e-3);
      EXPECT_EQ(curve.punctured_needles[s], 1);
      EXPECT_EQ(curve.phase[s], InsertionPhase::Cutting);
    }
  }
  // Each needle's own curve: its indentation force until its puncture, its cutting force after (Alg 3.1 at its own
  // inserted depth), summing to the array's.
  ASSERT_EQ(curve.needle_force.size(), 2u);
  for (std::size_t s = 0; s < curve.depth.size(); ++s) {
    const double u = curve.depth[s];
    EXPECT_NEAR(curve.needle_force[0][s] + curve.needle_force[1][s], curve.force[s], 1e-15);
    if (u > 200 * um) EXPECT_NEAR(curve.needle_force[0][s], post_puncture_force(loads, u, 0.2e6, 0.2), 1e-15);
    if (u > 350 * um) {
      EXPECT_NEAR(curve.needle_force[1][s], post_puncture_force(loads, u - 50 * um, 0.2e6, 0.2), 1e-15);
    }
    if (u < 340 * um) {
      const double x = std::max(0.0, u - 50 * um) / (300 * um);
      EXPECT_NEAR(curve.needle_force[1][s], 0.03 * x * x, 2e-3) << u;
    }
  }
}

TEST(InsertionCurve, NeedleWithoutPunctureStopsTheCurve) {
  const auto mesh = needle_mesh(needle::Shape::Cylinder, 230 * um, 230 * um, 0, 1000 * um, 32, 4);
  const auto loads = post_puncture_loads(mesh);
  NeedleInsertion needle{quadratic_pre_curve(600 * um, 0.3, false), &loads, 0.2e6, 0.168, 0};
  const auto curve = insertion_curve({needle}, {2000 * um, 10});
  EXPECT_EQ(curve.status, InsertionStatus::NoPuncture);
  EXPECT_THAT(curve.reason, HasSubstr("did not puncture"));
  EXPECT_TRUE(curve.punctures.empty());
  EXPECT_DOUBLE_EQ(curve.depth.back(), 600 * um);
  for (auto phase : curve.phase) EXPECT_EQ(phase, InsertionPhase::Indentation);

  NeedleInsertion bad = needle;
  bad.pre_puncture.curve.depth[2] = bad.pre_puncture.curve.depth[1];
  expect_invalid([&] { insertion_curve({bad}); }, "not monotonic");
  bad = needle;
  bad.stiffness = -1;
  expect_invalid([&] { insertion_curve({bad}); }, "stiffness");
}

}  // namespace
