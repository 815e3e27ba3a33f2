// Post-puncture force against closed forms (§3.6.2): a flat-ended cylinder carries K·S·(tip area) at every inserted
// depth; a blunt cone's β-load integrates to the analytic value for its slope, and the needlekit reading of
// Algorithm 3.1 converges to it at first order in the axial mesh size (second order around the axis).
#include <gtest/gtest.h>

#include <cmath>

#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

using namespace needlekit;
using namespace needlekit::insertion;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double um = 1e-6;

TEST(PostPunctureVerification, FlatCylinderForceIsStiffnessTimesScaleTimesTipArea) {
  for (double unit : {1e-6, 1.0}) {  // µm and m scale
    const double r = 115 * unit;
    const auto mesh = needle::needle_surface_mesh({needle::Shape::Cylinder, 2 * r, 2 * r, 0, 1000 * unit}, {128, 8});
    const auto loads = post_puncture_loads(mesh);
    EXPECT_TRUE(loads.classification.beta.empty());
    const double polygon = 0.5 * 128 * r * r * std::sin(2 * kPi / 128);
    const double K = 0.2e6, S = 0.168;
    for (double h : {1e-3, 0.1, 0.5, 1.0, 1.5}) {
      const double depth = h * 1000 * unit;
      EXPECT_NEAR(post_puncture_force(loads, depth, K, S) / (K * S * polygon), 1.0, 1e-12) << h;
    }
    EXPECT_EQ(post_puncture_force(loads, 0, K, S), 0.0);
    EXPECT_NEAR(polygon / (kPi * r * r), 1.0, 5e-4);  // and the polygon is the disk to 4e-4
  }
}

// The continuum of the needlekit reading for a frustum of tip radius ρt, half-angle θ (tanθ = (R − ρt)/L), R the
// base radius (the reference radius): α pressure 1 on the tip disk, β pressure δ/R with δ = (ρ − ρt)/cosθ on the
// slope, dA = 2πρ da/cosθ. Load area within inserted depth h <= L:
//   G(h) = π ρt² + 2π tanθ (ρt h²/2 + tanθ h³/3) / (R cos²θ).
double cone_load_area(double tip_radius, double base_radius, double length, double h) {
  const double tan_t = (base_radius - tip_radius) / length;
  const double cos2 = 1 / (1 + tan_t * tan_t);
  return kPi * tip_radius * tip_radius +
         2 * kPi * tan_t * (tip_radius * h * h / 2 + tan_t * h * h * h / 3) / (base_radius * cos2);
}

TEST(PostPunctureVerification, BluntConeBetaLoadConvergesToItsAnalyticValue) {
  const double rt = 30 * um, R = 115 * um, L = 200 * um;  // tanθ = 0.425: the printed a·tanθ matters
  std::vector<double> errors;
  for (int axial : {4, 8, 16, 32, 64}) {
    const auto mesh = needle::needle_surface_mesh({needle::Shape::Cone, 2 * rt, 2 * R, 0, L}, {1024, axial});
    PostPunctureOptions options;
    options.cap_at_cutting_pressure = false;
    options.max_edge_fraction = 0;  // the mesh as it is: the refinement is the mesh's
    const auto loads = post_puncture_loads(mesh, {}, options);
    EXPECT_NEAR(loads.reference_radius / R, 1.0, 1e-12);
    const double beta = post_puncture_load_area(loads, L) - loads.alpha_area;
    const double exact = cone_load_area(rt, R, L, L) - kPi * rt * rt;
    errors.push_back(std::abs(beta / exact - 1));
    // Partial insertion too: clipped triangles agree with the analytic G(h) as well.
    const double half = post_puncture_load_area(loads, 0.5 * L) - loads.alpha_area;
    EXPECT_NEAR(half / (cone_load_area(rt, R, L, 0.5 * L) - kPi * rt * rt), 1.0, 6 * errors.back() + 1e-3);
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double rate = std::log2(errors[k - 1] / errors[k]);
    EXPECT_GT(rate, 0.8) << "refinement " << k << ": errors " << errors[k - 1] << " -> " << errors[k];
    EXPECT_LT(rate, 1.3) << "refinement " << k;
  }
  EXPECT_LT(errors.back(), 2e-3);  // 64 rings: within 0.2 % of the analytic slope load
}

TEST(PostPunctureVerification, SubdividingLongTrianglesMakesACoarseConeAccurate) {
  // The default bisection of loaded triangles longer than 2.5 % of the needle: a 2-ring cone is as good as a fine one.
  const double rt = 30 * um, R = 115 * um, L = 200 * um;
  const auto mesh = needle::needle_surface_mesh({needle::Shape::Cone, 2 * rt, 2 * R, 0, L}, {1024, 2});
  PostPunctureOptions options;
  options.cap_at_cutting_pressure = false;
  const auto loads = post_puncture_loads(mesh, {}, options);
  const double beta = post_puncture_load_area(loads, L) - loads.alpha_area;
  EXPECT_NEAR(beta / (cone_load_area(rt, R, L, L) - kPi * rt * rt), 1.0, 1e-2);
}

TEST(PostPunctureVerification, SharpBevelLoadConvergesUnderSubdivision) {
  // No closed form for the bevel face: successive refinements of the loaded triangles (halving max_edge_fraction)
  // change the load by less and less (observed ratio ~0.6 per halving), and the finest two agree within 0.5 %.
  const auto mesh = needle::needle_surface_mesh({needle::Shape::Bevel, 10 * um, 230 * um, 0, 1000 * um}, {64, 8});
  std::vector<double> g;
  for (double fraction : {0.1, 0.05, 0.025, 0.0125, 0.00625}) {
    PostPunctureOptions options;
    options.max_edge_fraction = fraction;
    g.push_back(post_puncture_load_area(post_puncture_loads(mesh, {}, options), 1000 * um));
  }
  for (std::size_t k = 2; k < g.size(); ++k)
    EXPECT_LT(std::abs(g[k] - g[k - 1]), 0.8 * std::abs(g[k - 1] - g[k - 2])) << k;
  EXPECT_LT(std::abs(g.back() / g[g.size() - 2] - 1), 5e-3);
}

TEST(PostPunctureVerification, SharpConeLoadIsRadiusOverCosTheta) {
  // A nearly sharp cone (tip 2 um): the slope load is ∫ (ρ/cosθ)/R dA, the tip disk negligible.
  const double rt = 1 * um, R = 115 * um, L = 1000 * um;
  const auto mesh = needle::needle_surface_mesh({needle::Shape::Cone, 2 * rt, 2 * R, 0, L}, {512, 64});
  const auto loads = post_puncture_loads(mesh);
  for (double h : {0.25 * L, 0.5 * L, L}) {
    const double model = post_puncture_load_area(loads, h);
    EXPECT_NEAR(model / cone_load_area(rt, R, L, h), 1.0, 2e-3) << h;
  }
}

}  // namespace
