// Buckling loads of uniform and tapered columns (Eqs 2.26–2.36, Table 4.1) against closed forms and an independent
// shooting solution; bending loads (Eqs 5.7, 5.8) against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "needlekit/analysis/bending.hpp"
#include "needlekit/analysis/buckling.hpp"
#include "needlekit/needle/section_properties.hpp"

using namespace needlekit;
using namespace needlekit::analysis;
using needle::NeedleGeometry;
using needle::Shape;

namespace {

// Independent check: shoot u'' = −P·u/EI(s) from the tip (u = 0, u' = 1) with RK4 and find the lowest root of
// u'(L) = 0: march P up from p_low (the uniform column of the weakest section, below the lowest eigenvalue) in 1%
// steps to the first sign change, then bisect.
double shooting_fixed_free(const std::function<double(double)>& ei, double length, double p_low) {
  auto end_slope = [&](double p) {
    const int steps = 4000;
    const double h = length / steps;
    double u = 0, v = 1, s = 0;
    auto f = [&](double s_, double u_) { return -p * u_ / ei(s_); };
    for (int i = 0; i < steps; ++i, s += h) {
      const double k1u = v, k1v = f(s, u);
      const double k2u = v + 0.5 * h * k1v, k2v = f(s + 0.5 * h, u + 0.5 * h * k1u);
      const double k3u = v + 0.5 * h * k2v, k3v = f(s + 0.5 * h, u + 0.5 * h * k2u);
      const double k4u = v + h * k3v, k4v = f(s + h, u + h * k3u);
      u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    return v;
  };
  double lo = p_low, hi = p_low;
  while (end_slope(hi) > 0) lo = hi, hi *= 1.01;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (end_slope(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(ColumnEigenvalue, UniformColumnsMatchEuler) {
  for (double scale : {1e-6, 1.0}) {
    const double ei = 3.7 * std::pow(scale, 4), length = 500 * scale;
    auto constant = [&](double) { return ei; };
    const double unit = ei / (length * length);
    EXPECT_NEAR(column_buckling_load(constant, length) / (M_PI * M_PI / 4 * unit), 1.0, 1e-9);  // Eq 2.26
    ColumnEigenvalueOptions pinned{EndCondition::FixedPinned, 200};
    // Fixed-pinned: tan(kL) = kL, kL = 4.4934094579 (Eq 2.31's 2.04π² is this value rounded).
    EXPECT_NEAR(column_buckling_load(constant, length, pinned) / (4.4934094579090642 * 4.4934094579090642 * unit), 1.0,
                1e-6);
    ColumnEigenvalueOptions fixed{EndCondition::FixedFixed, 200};
    EXPECT_NEAR(column_buckling_load(constant, length, fixed) / (4 * M_PI * M_PI * unit), 1.0, 1e-6);  // Eq 2.30
  }
}

TEST(ColumnEigenvalue, TaperedColumnMatchesShooting) {
  for (const NeedleGeometry& n : {NeedleGeometry{Shape::Cone, 30e-6, 150e-6, 0, 500e-6},
                                  NeedleGeometry{Shape::Cone, 70e-6, 80e-6, 20e-6, 500e-6},
                                  NeedleGeometry{Shape::Bevel, 30e-6, 120e-6, 0, 500e-6},
                                  NeedleGeometry{Shape::Bevel, 60e-6, 80e-6, 20e-6, 350e-6}}) {
    auto ei = [&](double s) { return 169e9 * needle::section_at(n, s).second_moment_min; };
    const double weakest = M_PI * M_PI / 4 * ei(0.0) / (n.length * n.length);
    const double reference = shooting_fixed_free(ei, n.length, weakest * 0.999);
    EXPECT_NEAR(column_buckling_load(ei, n.length) / reference, 1.0, 1e-6) << needle::to_string(n.shape);
  }
}

TEST(ColumnEigenvalue, RefinementConverges) {
  const NeedleGeometry cone{Shape::Cone, 30e-6, 150e-6, 0, 500e-6};
  auto ei = [&](double s) { return needle::section_at(cone, s).second_moment_min; };
  const double fine = column_buckling_load(ei, cone.length, {EndCondition::FixedFree, 800});
  const double e50 = std::abs(column_buckling_load(ei, cone.length, {EndCondition::FixedFree, 50}) / fine - 1);
  const double e100 = std::abs(column_buckling_load(ei, cone.length, {EndCondition::FixedFree, 100}) / fine - 1);
  EXPECT_LT(e100, 1e-6);
  EXPECT_GT(std::log2(e50 / e100), 2.5);  // Richardson-extrapolated second-order scheme: better than second order
}

TEST(TaperedColumnFactor, IsPiSquaredOverFourForACylinderAndGrowsWithTheTip) {
  EXPECT_NEAR(tapered_column_factor({Shape::Cylinder, 80e-6, 80e-6, 0, 500e-6}) / (M_PI * M_PI / 4), 1.0, 1e-9);
  // At a fixed base, a thicker tip stiffens the column: m rises towards π²/4.
  double previous = 0;
  for (double ratio : {0.1, 0.2, 0.5, 0.8, 0.99}) {
    const double m = tapered_column_factor({Shape::Cone, ratio * 100e-6, 100e-6, 0, 500e-6});
    EXPECT_GT(m, previous);
    EXPECT_LT(m, M_PI * M_PI / 4);
    previous = m;
  }
  // Timoshenko & Gere (1961), §2.13: a fixed-free bar whose I varies as (x/a)^4 (a cone), I1/I2 = 0.1 → m = 1.202
  // is for a bar tapered to a point; our frustum with D1/D2 = 0.1^(1/4) has the same I1/I2 and must lie between the
  // sharp-cone value and π²/4.
  const double m_frustum = tapered_column_factor({Shape::Cone, std::pow(0.1, 0.25) * 100e-6, 100e-6, 0, 500e-6});
  EXPECT_GT(m_frustum, 1.0);
  EXPECT_LT(m_frustum, M_PI * M_PI / 4);
}

TEST(Buckling, EulerAndJohnsonAgreeAtTheColumnConstant) {
  const double e = 169e9, sy = 7e9, area = 5e-9;
  const double cc = column_constant(e, sy);
  const double i = area * std::pow(cc > 0 ? 1e-5 : 1, 2);  // r = 1e-5 m
  const double r = std::sqrt(i / area);
  const double length_at_cc = cc * r / 2.0;  // K = 2
  EXPECT_NEAR(johnson_critical_load(area, sy, e, cc) / euler_critical_load(e, i, length_at_cc, 2.0), 1.0, 1e-12);
  EXPECT_NEAR(johnson_critical_load(area, sy, e, cc), area * sy / 2, 1e-9 * area * sy);
}

TEST(Buckling, Table4_1ForSiliconCylinders) {
  const auto silicon = materials::material_preset("silicon");
  BucklingOptions euler_only;
  euler_only.johnson_for_short_columns = false;
  const NeedleGeometry solid{Shape::Cylinder, 80e-6, 80e-6, 0, 500e-6};
  const double table = 0.25 * 169e9 * std::pow(M_PI, 3) * std::pow(80e-6, 4) / (64 * 500e-6 * 500e-6);
  EXPECT_NEAR(critical_buckling_load(solid, silicon, euler_only).critical_load / table, 1.0, 1e-12);
  const NeedleGeometry hollow{Shape::Cylinder, 80e-6, 80e-6, 20e-6, 500e-6};
  const double table_hollow =
      0.25 * 169e9 * std::pow(M_PI, 3) * (std::pow(80e-6, 4) - std::pow(20e-6, 4)) / (64 * 500e-6 * 500e-6);
  EXPECT_NEAR(critical_buckling_load(hollow, silicon, euler_only).critical_load / table_hollow, 1.0, 1e-12);
  // Practical K = 2.1.
  BucklingOptions practical = euler_only;
  practical.effective_length = EffectiveLengthValue::Practical;
  EXPECT_NEAR(critical_buckling_load(solid, silicon, practical).critical_load / (table * 4 / (2.1 * 2.1)), 1.0, 1e-12);
  // A stout cylinder is a short column: Johnson, and lower than Euler.
  const NeedleGeometry stout{Shape::Cylinder, 300e-6, 300e-6, 0, 300e-6};
  const auto johnson = critical_buckling_load(stout, silicon);
  EXPECT_EQ(johnson.method, BucklingMethod::Johnson);
  EXPECT_LT(johnson.critical_load, critical_buckling_load(stout, silicon, euler_only).critical_load);
  // No yield strength: C_c is not assessed and said so.
  const auto no_yield = critical_buckling_load(solid, {"x", 4e9, std::nullopt, std::nullopt, "test"});
  EXPECT_EQ(no_yield.column_constant, 0);
  EXPECT_NE(no_yield.note.find("no yield_strength"), std::string::npos);
}

TEST(Bending, ClosedFormsOfEqs5_7And5_8MatchTheSectionScan) {
  const double sigma = 40e6, length = 400e-6;
  // Solid cylinder, Eq 5.7, against the scan path (a hollow needle with a negligible bore).
  const NeedleGeometry solid{Shape::Cylinder, 70e-6, 70e-6, 0, length};
  NeedleGeometry nearly_solid = solid;
  nearly_solid.bore_diameter = 1e-12;
  EXPECT_NEAR(critical_bending_load(solid, sigma) / (sigma * M_PI * std::pow(70e-6, 3) / (32 * length)), 1.0, 1e-12);
  EXPECT_NEAR(critical_bending_load(nearly_solid, sigma) / critical_bending_load(solid, sigma), 1.0, 1e-9);
  // Cone: Eq 5.8 for t >= 1.5 and the base branch for t < 1.5, both against the scan.
  for (double d2 : {70e-6 * 1.2, 70e-6 * 1.5, 70e-6 * 3, 300e-6}) {
    const NeedleGeometry cone{Shape::Cone, 70e-6, d2, 0, length};
    NeedleGeometry scanned = cone;
    scanned.bore_diameter = 1e-12;
    EXPECT_NEAR(critical_bending_load(scanned, sigma) / critical_bending_load(cone, sigma), 1.0, 1e-7) << d2;
  }
  // Continuity at t = 1.5: 27·0.5/128·D1³ = D2³/32 with D2 = 1.5·D1.
  EXPECT_NEAR(27 * 0.5 / 128, std::pow(1.5, 3) / 32, 1e-15);
  // Hollow cylinder: σ·π(D⁴ − D3⁴)/(32·D·L).
  const NeedleGeometry tube{Shape::Cylinder, 80e-6, 80e-6, 30e-6, length};
  const double tube_closed = sigma * M_PI * (std::pow(80e-6, 4) - std::pow(30e-6, 4)) / (32 * 80e-6 * length);
  EXPECT_NEAR(critical_bending_load(tube, sigma) / tube_closed, 1.0, 1e-9);
}

TEST(AngledInsertion, Eqs5_3And5_4) {
  EXPECT_DOUBLE_EQ(angled_buckling_force(-0.5, 0), 0.5);
  EXPECT_DOUBLE_EQ(angled_bending_force(-0.5, 0), 0);
  EXPECT_NEAR(angled_buckling_force(0.5, M_PI / 6), 0.5 / std::cos(M_PI / 6), 1e-15);
  EXPECT_NEAR(angled_bending_force(0.5, M_PI / 6), 0.5 * std::tan(M_PI / 6), 1e-15);
  EXPECT_THROW(angled_bending_force(0.5, M_PI / 2), std::invalid_argument);
  EXPECT_THROW(angled_buckling_force(0.5, -0.1), std::invalid_argument);
}
