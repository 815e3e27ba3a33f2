// The performance index (Eqs 4.25, 5.9): hand calculations and the reason given for every zero.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/analysis/skin_permeation.hpp"
#include "needlekit/core/errors.hpp"

using namespace needlekit;
using namespace needlekit::analysis;
using testing::HasSubstr;

namespace {

ArrayDesign table_6_1_cone() {
  ArrayDesign d;
  d.needle = {needle::Shape::Cone, 30e-6, 150e-6, 0, 500e-6};
  d.material = materials::material_preset("silicon");
  d.needles_per_row = 10;
  d.width = 1e-2;
  return d;
}

}  // namespace

TEST(PunctureModel, Eq4_2AndEq4_3ByHand) {
  const auto skin = skin_puncture_model();
  // A = 7088.218 um² (95 um cylinder): F = 0.00019·A − 0.66 = 0.686761 N; d = 160 um·ln(F/0.0183) = 580.03 um.
  const double area = M_PI / 4 * 95e-6 * 95e-6;
  EXPECT_NEAR(puncture_force(area, skin), 0.00019 * (M_PI / 4 * 95 * 95) - 0.66, 1e-12);
  EXPECT_NEAR(skin_deformation(area, skin).depth * 1e6, 160 * std::log(0.6867615 / 0.0183), 1e-3);
  // The small-tip limit F(A) = α: 67.4 um for skin, 66.6 um for brain (notes).
  EXPECT_NEAR(std::sqrt(4 * small_tip_area_limit(skin) / M_PI) * 1e6, 67.4, 0.05);
  EXPECT_NEAR(std::sqrt(4 * small_tip_area_limit(brain_puncture_model()) / M_PI) * 1e6, 66.6, 0.05);
  // Continuity is not promised by the dissertation; the switch is on the area (F > α).
  EXPECT_FALSE(skin_deformation(small_tip_area_limit(skin) * 1.001, skin).small_tip_branch);
  EXPECT_TRUE(skin_deformation(small_tip_area_limit(skin) * 0.999, skin).small_tip_branch);
}

TEST(PerformanceIndex, ConeOfTable6_1ByHand) {
  const auto r = performance_index(table_6_1_cone(), InsertionConditions{});
  ASSERT_EQ(r.status, PerformanceStatus::Ok) << r.reason;
  const double h = 500e-6 - 0.0608e6 * (M_PI / 4 * 30e-6 * 30e-6);
  const double b = 30e-6 + 120e-6 * h / 500e-6;
  const double q = M_PI / 12 * (30e-6 * 30e-6 + 30e-6 * b + b * b);
  EXPECT_NEAR(r.q_factor / q, 1.0, 1e-12);
  EXPECT_NEAR(r.performance_index / (q / (1e-3 * 1e-3 * 50e-6)), 1.0, 1e-12);
  EXPECT_TRUE(r.buckling_ok);
  EXPECT_TRUE(r.reason.empty());
}

TEST(PerformanceIndex, EveryZeroSaysWhy) {
  // Too short: the 95 um cylinder of §6.3.1 deforms the skin by 580 um > 500 um.
  ArrayDesign cylinder = table_6_1_cone();
  cylinder.needle = {needle::Shape::Cylinder, 95e-6, 95e-6, 0, 500e-6};
  auto r = performance_index(cylinder, InsertionConditions{});
  EXPECT_EQ(r.status, PerformanceStatus::TooShort);
  EXPECT_EQ(r.performance_index, 0);
  EXPECT_THAT(r.reason, HasSubstr("does not reach the target depth"));

  // Spacing: 25 needles of 150 um on 1 cm violate w >= 3·n·D2 = 11.25 mm.
  ArrayDesign crowded = table_6_1_cone();
  crowded.needles_per_row = 25;
  r = performance_index(crowded, InsertionConditions{});
  EXPECT_EQ(r.status, PerformanceStatus::ConstraintViolated);
  EXPECT_THAT(r.reason, HasSubstr("w >= beta*n*D2"));

  // Buckling: a long thin PLGA cone in brain.
  ArrayDesign slender = table_6_1_cone();
  slender.needle = {needle::Shape::Cone, 70e-6, 100e-6, 0, 5e-3};
  slender.material = materials::material_preset("plga");
  InsertionConditions brain;
  brain.tissue = brain_puncture_model();
  brain.target_depth = 1e-3;
  r = performance_index(slender, brain);
  EXPECT_EQ(r.status, PerformanceStatus::Buckles);
  EXPECT_THAT(r.reason, HasSubstr("buckles"));

  // Bending without buckling: a 70 um stainless-steel cylinder, 1 mm long, inserted at 60 degrees
  // (P_cr ≈ 0.56 N > |F|/cos θ ≈ 0.14 N; P_Be ≈ 6.5 mN < |F|·tan θ ≈ 0.12 N).
  ArrayDesign steel = table_6_1_cone();
  steel.needle = {needle::Shape::Cylinder, 70e-6, 70e-6, 0, 1000e-6};
  steel.material = materials::material_preset("stainless-steel");
  InsertionConditions angled;
  angled.angle = M_PI / 3;
  r = performance_index(steel, angled);
  EXPECT_EQ(r.status, PerformanceStatus::Bends) << r.reason;
  EXPECT_THAT(r.reason, HasSubstr("bends"));
  ASSERT_TRUE(r.critical_bending_load.has_value());
  EXPECT_NEAR(r.bending_force, std::abs(r.puncture_force) * std::tan(M_PI / 3), 1e-12);
}

TEST(PerformanceIndex, MissingAllowableStressIsReportedAsNotAssessed) {
  ArrayDesign d = table_6_1_cone();
  d.material = {"custom", 4e9, std::nullopt, std::nullopt, "user"};
  InsertionConditions angled;
  angled.angle = 0.2;
  const auto r = performance_index(d, angled);
  EXPECT_FALSE(r.critical_bending_load.has_value());
  EXPECT_FALSE(r.bending_ok.has_value());
  EXPECT_THAT(r.notes, testing::Contains(HasSubstr("bending not assessed")));
}

TEST(PerformanceIndex, BadInputThrowsNamingTheField) {
  ArrayDesign d = table_6_1_cone();
  d.needle.tip_diameter = 200e-6;
  EXPECT_THAT([&] { performance_index(d, {}); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("needle.tip_diameter")));
  d = table_6_1_cone();
  d.needle.bore_diameter = 40e-6;
  EXPECT_THAT([&] { performance_index(d, {}); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("needle.bore_diameter")));
  d = table_6_1_cone();
  d.needle.length = std::nan("");
  EXPECT_THAT([&] { performance_index(d, {}); }, testing::ThrowsMessage<InvalidInput>(HasSubstr("needle.length")));
  d = table_6_1_cone();
  InsertionConditions c;
  c.angle = M_PI / 2;
  EXPECT_THAT([&] { performance_index(d, c); }, testing::ThrowsMessage<InvalidInput>(HasSubstr("insertion.angle")));
}

TEST(PerformanceIndex, ScaleInvariantWhenTheTissueModelScalesToo) {
  // The index is 1/length; with F(A), α, τ and K rescaled consistently the µm and m designs agree.
  ArrayDesign small = table_6_1_cone();
  ArrayDesign large = small;
  const double k = 1e6;
  large.needle = {needle::Shape::Cone, 30e-6 * k, 150e-6 * k, 0, 500e-6 * k};
  large.width *= k;
  InsertionConditions c_small, c_large;
  c_large.tissue.force_law.slope /= k * k;  // same force for the scaled area
  c_large.tissue.tau /= k;
  c_large.tissue.small_tip_slope /= k;
  c_large.target_depth *= k;
  large.material.youngs_modulus /= k * k;  // same buckling load for the scaled column (E·I/L² ∝ E·k²)
  const auto a = performance_index(small, c_small);
  const auto b = performance_index(large, c_large);
  EXPECT_NEAR(a.deformation * k / b.deformation, 1.0, 1e-12);
  EXPECT_NEAR(a.performance_index / (b.performance_index * k), 1.0, 1e-10);
  EXPECT_NEAR(a.buckling.critical_load / b.buckling.critical_load, 1.0, 1e-9);
}
