// Patch fitting on analytic surfaces (dissertation §5.7): plane, cylinder, sphere; invariance under rigid motions of
// the surface; metre vs micrometre scale.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>

#include "../support/analytic_surfaces.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"
#include "needlekit/patch/spring_geodesics.hpp"

namespace needlekit::patch {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

PatchDesign design_of(double width, int n, double scale = 1) {
  PatchDesignOptions o;
  o.needles_u = o.needles_v = n;
  o.width_u = o.width_v = width;
  o.stiffness_u = o.stiffness_v = o.stiffness_diagonal = 1e3;
  o.needle = {needle::Shape::Cylinder, 70e-6 * scale, 70e-6 * scale, 0, 400e-6 * scale};
  o.material = materials::material_preset("su-8");
  return patch_design(o);
}

geometry::TriangleMesh transformed(geometry::TriangleMesh mesh, const Eigen::Matrix3d& rotation,
                                   const Eigen::Vector3d& shift, double scale = 1) {
  for (auto& v : mesh.vertices) v = scale * (rotation * v) + shift;
  return mesh;
}

// The open cylinder of radius r about the X axis (the generators along X), top line at z = r.
geometry::TriangleMesh x_cylinder(double r, double length, int around, int along) {
  geometry::TriangleMesh mesh = test::open_cylinder_mesh(r, length, around, along);
  // (x, y, z) -> (z - length/2, x, y): a cyclic permutation, a proper rotation, keeps the outward orientation.
  for (auto& v : mesh.vertices) v = Eigen::Vector3d(v.z() - length / 2, v.x(), v.y());
  return mesh;
}

double total_energy(const PatchDesign& d, const FittedPatch& f) {
  double total = 0;
  for (double e : spring_energies(d, f.positions)) total += e;
  return total;
}

FitOptions flexible(double cap, WalkMethod walk = WalkMethod::CuttingPlane) {
  FitOptions o;
  o.kind = PatchKind::Flexible;
  o.flexible.max_spring_energy = cap;
  o.flexible.walk = walk;
  return o;
}

TEST(PatchFitting, OnAPlaneRigidAndFlexibleCoincideWithZeroEnergyAndZeroAngle) {
  const geometry::SurfaceMesh plane(test::plane_grid_mesh(0.02, 37));
  const PatchDesign d = design_of(10e-3, 10);
  Placement placement;
  placement.center = {0.0013, -0.0021, 0};
  placement.rotation = 0.3;
  const PatchFrame frame = patch_frame(plane, placement, std::hypot(10e-3, 10e-3), 400e-6);
  const FittedPatch rigid = fit_patch(plane, d, frame, {PatchKind::Rigid, {}, {}});
  const FittedPatch flex = fit_patch(plane, d, frame, flexible(kInf));
  ASSERT_EQ(rigid.status, FitStatus::Ok) << rigid.reason;
  ASSERT_EQ(flex.status, FitStatus::Ok) << flex.reason;
  for (int k = 0; k < d.node_count(); ++k) {
    EXPECT_NEAR((rigid.positions[k] - flex.positions[k]).norm(), 0, 1e-12) << "node " << k;
    EXPECT_NEAR(rigid.positions[k].z(), 0, 1e-15);
  }
  EXPECT_LT(total_energy(d, flex), 1e-20);
  const PatchEvaluation e = evaluate_needles(plane, d, flex);
  EXPECT_NEAR(e.angle.max, 0, 1e-9);
  EXPECT_EQ(e.penetrating, 100);
  EXPECT_NEAR(e.travel.min, 400e-6, 1e-12);
}

TEST(PatchFitting, OnATiltedPlaneApproachedAlongTheNormalTheFitsCoincide) {
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  const geometry::SurfaceMesh plane(transformed(test::plane_grid_mesh(0.02, 29), tilt, {0.1, 0.2, 0.3}));
  const PatchDesign d = design_of(10e-3, 10);
  Placement placement;
  placement.center = Eigen::Vector3d(0.1, 0.2, 0.3);
  placement.approach = Approach::SurfaceNormal;
  const PatchFrame frame = patch_frame(plane, placement, 0.015, 400e-6);
  const FittedPatch rigid = fit_patch(plane, d, frame, {PatchKind::Rigid, {}, {}});
  const FittedPatch flex = fit_patch(plane, d, frame, flexible(kInf));
  for (int k = 0; k < d.node_count(); ++k) EXPECT_NEAR((rigid.positions[k] - flex.positions[k]).norm(), 0, 1e-12);
  EXPECT_LT(total_energy(d, flex), 1e-20);
  EXPECT_NEAR(evaluate_needles(plane, d, flex).angle.max, 0, 1e-7);
}

TEST(PatchFitting, OnACylinderTheFlexiblePatchWrapsWithoutStretchAlongTheGenerators) {
  const double r = 0.02;
  const geometry::SurfaceMesh cylinder(x_cylinder(r, 0.06, 512, 24));
  const PatchDesign d = design_of(10e-3, 10);
  Placement placement;
  placement.center = {0.0, 0.0, r};
  const PatchFrame frame = patch_frame(cylinder, placement, 0.015, 400e-6);
  // The straightest geodesic (unfolding) is exact on the developable cylinder; Alg 5.3's cutting plane is exact
  // along the generators and around the circumference, and cuts an ellipse instead of a helix for the diagonals.
  for (const auto& [walk, generator_tolerance] : {std::pair{WalkMethod::Unfolding, 1e-9},
                                                  std::pair{WalkMethod::CuttingPlane, 3e-4}}) {
  SCOPED_TRACE(walk == WalkMethod::Unfolding ? "unfolding" : "cutting plane");
  const FittedPatch fit = fit_patch(cylinder, d, frame, flexible(kInf, walk));
  ASSERT_EQ(fit.status, FitStatus::Ok) << fit.reason;
  const double sagitta = r * (1 - std::cos(std::numbers::pi / 512));
  for (int k = 0; k < d.node_count(); ++k) {
    EXPECT_NEAR(std::hypot(fit.positions[k].y(), fit.positions[k].z()), r, 1.01 * sagitta) << "node " << k;
  }
  for (const Spring& s : d.springs) {
    const Eigen::Vector3d a = fit.positions[s.a], b = fit.positions[s.b];
    if (s.direction == SpringDirection::U) {
      EXPECT_NEAR((b - a).norm(), s.rest_length, generator_tolerance * s.rest_length);  // along a generator
    }
    if (s.direction == SpringDirection::V) {
      // Around the circumference: the arc (geodesic) between the two nodes is the rest length.
      const double arc = r * std::abs(std::remainder(std::atan2(b.y(), b.z()) - std::atan2(a.y(), a.z()),
                                                     2 * std::numbers::pi));
      EXPECT_NEAR(arc, s.rest_length, 2e-3 * s.rest_length);
    }
  }
  // The needles follow the normals: small angles, all the way in.
  const PatchEvaluation e = evaluate_needles(cylinder, d, fit);
  EXPECT_LT(e.angle.max, 0.03);
  EXPECT_EQ(e.penetrating, 100);
  // Exact geodesic distances between the fitted nodes: the rest length for every spring when the traverse unfolds
  // (the cylinder is developable); within 6e-4 along U and V with the cutting plane (its diagonals cut ellipses).
  const SpringGeodesics g = spring_geodesics(cylinder, d, fit);
  EXPECT_EQ(g.not_converged, 0);
  for (std::size_t s = 0; s < d.springs.size(); ++s) {
    const bool axial = d.springs[s].direction == SpringDirection::U || d.springs[s].direction == SpringDirection::V;
    if (walk == WalkMethod::Unfolding) EXPECT_NEAR(g.strain[s], 0, 1e-6) << "spring " << s;
    if (axial) EXPECT_NEAR(g.strain[s], 0, 6e-4) << "spring " << s;
  }
  }
}

TEST(PatchFitting, RigidPatchOnACylinderTouchesAlongTheTopAndTiltsTheOuterNeedles) {
  const double r = 0.02;
  const geometry::SurfaceMesh cylinder(x_cylinder(r, 0.06, 512, 24));
  const PatchDesign d = design_of(10e-3, 10);
  Placement placement;
  placement.center = {0.0, 0.0, r};
  const FittedPatch fit = fit_patch(cylinder, d, patch_frame(cylinder, placement, 0.015, 400e-6), {PatchKind::Rigid, {}, {}});
  const PatchEvaluation e = evaluate_needles(cylinder, d, fit);
  // The outermost row at y = 4.5 mm: θ = asin(4.5/20).
  EXPECT_NEAR(e.angle.max, std::asin(4.5e-3 / r), 2e-3);
  // The plate touches the top generator (z = r); the outermost needles stop short by the sag of the cylinder.
  const double sag = r - std::sqrt(r * r - 4.5e-3 * 4.5e-3);
  EXPECT_NEAR(e.travel.min, 400e-6 - sag, 2e-6);
}

TEST(PatchFitting, OnASphereTheSpringEnergyFallsAsTheRadiusGrows) {
  const PatchDesign d = design_of(10e-3, 10);
  double previous = kInf;
  for (const double r : {0.015, 0.03, 0.06}) {
    const geometry::SurfaceMesh sphere(test::icosphere_mesh(r, 6));
    Placement placement;
    placement.center = {0, 0, r};
    const FittedPatch fit = fit_patch(sphere, d, patch_frame(sphere, placement, 0.015, 400e-6), flexible(kInf));
    ASSERT_EQ(fit.status, FitStatus::Ok) << fit.reason;
    const double energy = total_energy(d, fit);
    EXPECT_GT(energy, 0);
    EXPECT_LT(energy, previous) << "radius " << r;
    previous = energy;
  }
}

TEST(PatchFitting, SmallEnergyCapKeepsThePatchRigidLargeCapConforms) {
  const double r = 0.02;
  const geometry::SurfaceMesh sphere(test::icosphere_mesh(r, 6));
  const PatchDesign d = design_of(10e-3, 10);
  Placement placement;
  placement.center = {0, 0, r};
  const PatchFrame frame = patch_frame(sphere, placement, 0.015, 400e-6);
  const FittedPatch rigid = fit_patch(sphere, d, frame, {PatchKind::Rigid, {}, {}});
  const FittedPatch stiff = fit_patch(sphere, d, frame, flexible(1e-18));
  const FittedPatch soft = fit_patch(sphere, d, frame, flexible(kInf));
  // E_cri → 0: the rigid patch's shape, moved along the approach only (it hangs from its first node, the rigid
  // plate from the highest surface point under it).
  const Eigen::Vector3d shift = stiff.positions[0] - rigid.positions[0];
  EXPECT_LT(shift.cross(frame.approach).norm(), 1e-9);
  double stiff_gap = 0;
  for (int k = 0; k < d.node_count(); ++k) {
    stiff_gap = std::max(stiff_gap, (stiff.positions[k] - rigid.positions[k] - shift).norm());
  }
  EXPECT_LT(stiff_gap, 1e-6);
  const PatchEvaluation es = evaluate_needles(sphere, d, stiff), ef = evaluate_needles(sphere, d, soft);
  EXPECT_GT(es.angle.max, 5 * ef.angle.max);
  EXPECT_GT(ef.penetrating, es.penetrating);
}

TEST(PatchFitting, TheFitMovesWithTheSurface) {
  const double r = 0.02;
  const geometry::TriangleMesh base = test::icosphere_mesh(r, 5);
  const PatchDesign d = design_of(10e-3, 8);
  Placement placement;
  placement.center = {0.003, 0.002, std::sqrt(r * r - 13e-6)};
  const FittedPatch reference = fit_patch(geometry::SurfaceMesh(base), d,
                                          patch_frame(geometry::SurfaceMesh(base), placement, 0.015, 400e-6), flexible(1e-5));
  // Turn the sphere by α about Z and shift it; the patch, turned by the same α, must follow.
  const double alpha = 0.7;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d shift(0.5, -0.25, 0.125);
  const geometry::SurfaceMesh moved(transformed(base, turn, shift));
  Placement moved_placement = placement;
  moved_placement.center = turn * placement.center + shift;
  moved_placement.rotation = alpha;
  const FittedPatch fit = fit_patch(moved, d, patch_frame(moved, moved_placement, 0.015, 400e-6), flexible(1e-5));
  for (int k = 0; k < d.node_count(); ++k) {
    EXPECT_NEAR((fit.positions[k] - (turn * reference.positions[k] + shift)).norm(), 0, 1e-9) << "node " << k;
  }
}

TEST(PatchFitting, MetreAndMicrometreScalesAgree) {
  const double r = 0.02;
  const PatchDesign d = design_of(10e-3, 8);
  const PatchDesign small = design_of(10e-9, 8, 1e-6);
  Placement placement;
  placement.center = {0.001, 0.002, std::sqrt(r * r - 5e-6)};
  const geometry::TriangleMesh mesh = test::icosphere_mesh(r, 5);
  const geometry::SurfaceMesh big_sphere(mesh);
  const geometry::SurfaceMesh small_sphere(transformed(mesh, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), 1e-6));
  Placement small_placement = placement;
  small_placement.center *= 1e-6;
  small_placement.max_center_distance *= 1e-6;
  const FittedPatch big = fit_patch(big_sphere, d, patch_frame(big_sphere, placement, 0.015, 400e-6), flexible(kInf));
  const FittedPatch tiny =
      fit_patch(small_sphere, small, patch_frame(small_sphere, small_placement, 0.015e-6, 400e-12), flexible(kInf));
  for (int k = 0; k < d.node_count(); ++k) EXPECT_NEAR((tiny.positions[k] * 1e6 - big.positions[k]).norm(), 0, 1e-10);
  NeedleEvaluationOptions options;
  const PatchEvaluation eb = evaluate_needles(big_sphere, d, big);
  EXPECT_GT(eb.angle.max, 0);
  // The tiny needles' angles (geometry only; the tissue model is not scale-free).
  for (int k = 0; k < d.node_count(); ++k) {
    EXPECT_NEAR(tiny.normals[k].dot(big.normals[k]), 1, 1e-12);
  }
}

}  // namespace
}  // namespace needlekit::patch
