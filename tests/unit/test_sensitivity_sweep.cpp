// One-at-a-time sweeps (Figs 6.18/6.19): every point equals a direct evaluation, invalid geometries are reported
// as points, bad ranges are errors naming --vary.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "needlekit/analysis/sensitivity_sweep.hpp"
#include "needlekit/core/errors.hpp"

using namespace needlekit;
using namespace needlekit::analysis;
using testing::HasSubstr;

namespace {

ArrayDesign table_6_1(needle::Shape shape, double tip, double base) {
  ArrayDesign d;
  d.needle = {shape, tip, base, 0, 500e-6};
  d.material = materials::material_preset("silicon");
  d.needles_per_row = 10;
  d.width = 1e-2;
  return d;
}

}  // namespace

TEST(SensitivitySweep, PointsEqualDirectEvaluations) {
  const ArrayDesign cone = table_6_1(needle::Shape::Cone, 30e-6, 150e-6);
  const SweepResult sweep = sensitivity_sweep(cone, {}, {}, {SweepParameter::BaseDiameter, 50e-6, 300e-6, 10e-6});
  ASSERT_EQ(sweep.points.size(), 26u);  // 50, 60, ..., 300 um inclusive
  EXPECT_EQ(sweep.parameter, SweepParameter::BaseDiameter);
  for (const SweepPoint& point : sweep.points) {
    ArrayDesign direct = cone;
    direct.needle.base_diameter = point.value;
    EXPECT_EQ(point.result.performance_index, performance_index(direct, {}).performance_index) << point.value;
  }
  // §6.3.1: the index grows with the base diameter (Fig 6.18).
  EXPECT_GT(sweep.points.back().result.performance_index, sweep.points.front().result.performance_index);
}

TEST(SensitivitySweep, InvalidGeometryIsAPointNotAnException) {
  const ArrayDesign cone = table_6_1(needle::Shape::Cone, 30e-6, 150e-6);
  const SweepResult sweep = sensitivity_sweep(cone, {}, {}, {SweepParameter::TipDiameter, 100e-6, 200e-6, 50e-6});
  ASSERT_EQ(sweep.points.size(), 3u);
  EXPECT_NE(sweep.points[1].result.status, PerformanceStatus::ConstraintViolated);  // D1 = D2 = 150 um is valid
  EXPECT_EQ(sweep.points[2].result.status, PerformanceStatus::ConstraintViolated);  // D1 = 200 > D2
  EXPECT_THAT(sweep.points[2].result.reason, HasSubstr("tip_diameter"));
  EXPECT_EQ(sweep.points[2].result.performance_index, 0);
}

TEST(SensitivitySweep, CylinderTipAndBaseVaryTogether) {
  const ArrayDesign cylinder = table_6_1(needle::Shape::Cylinder, 95e-6, 95e-6);
  for (const SweepParameter parameter : {SweepParameter::TipDiameter, SweepParameter::BaseDiameter}) {
    const SweepResult sweep = sensitivity_sweep(cylinder, {}, {}, {parameter, 40e-6, 60e-6, 10e-6});
    ASSERT_EQ(sweep.points.size(), 3u);
    for (const SweepPoint& point : sweep.points) {
      EXPECT_EQ(point.design.needle.tip_diameter, point.value);
      EXPECT_EQ(point.design.needle.base_diameter, point.value);
      EXPECT_NE(point.result.status, PerformanceStatus::ConstraintViolated) << point.result.reason;
    }
  }
}

TEST(SensitivitySweep, ConditionsAndCountsCanBeVaried) {
  const ArrayDesign cone = table_6_1(needle::Shape::Cone, 30e-6, 150e-6);
  const SweepResult rows = sensitivity_sweep(cone, {}, {}, {SweepParameter::NeedlesPerRow, 5, 25, 5});
  ASSERT_EQ(rows.points.size(), 5u);
  EXPECT_EQ(rows.points.back().design.needles_per_row, 25);
  const SweepResult depth = sensitivity_sweep(cone, {}, {}, {SweepParameter::TargetDepth, 50e-6, 500e-6, 450e-6});
  ASSERT_EQ(depth.points.size(), 2u);
  EXPECT_EQ(depth.points[1].result.status, PerformanceStatus::TooShort);  // L < d + 500 um
}

TEST(SensitivitySweep, BadRangesNameVary) {
  const ArrayDesign cone = table_6_1(needle::Shape::Cone, 30e-6, 150e-6);
  for (const SweepOptions& bad : {SweepOptions{SweepParameter::Length, 300e-6, 500e-6, 0},
                                  SweepOptions{SweepParameter::Length, 300e-6, 500e-6, -1e-6},
                                  SweepOptions{SweepParameter::Length, 500e-6, 300e-6, 1e-6},
                                  SweepOptions{SweepParameter::NeedlesPerRow, 5, 25, 0.5}}) {
    try {
      sensitivity_sweep(cone, {}, {}, bad);
      ADD_FAILURE() << "no error for step " << bad.step;
    } catch (const InvalidInput& error) {
      EXPECT_THAT(error.what(), HasSubstr("--vary"));
    }
  }
  EXPECT_EQ(sweep_parameter_from_string("bore_diameter"), SweepParameter::BoreDiameter);
  EXPECT_THROW(sweep_parameter_from_string("diameter"), InvalidInput);
}
