#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"

using namespace needlekit;
using units::Dimension;
using units::parse_quantity;

TEST(Units, ParsesTheIssueExamples) {
  EXPECT_DOUBLE_EQ(parse_quantity("230 um", Dimension::Length, "k"), 230e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("1 cm", Dimension::Length, "k"), 1e-2);
  EXPECT_DOUBLE_EQ(parse_quantity("169 GPa", Dimension::Pressure, "k"), 169e9);
  EXPECT_DOUBLE_EQ(parse_quantity("0.05 mJ", Dimension::Energy, "k"), 5e-5);
  EXPECT_DOUBLE_EQ(parse_quantity("30 deg", Dimension::Angle, "k"), M_PI / 6);
  EXPECT_DOUBLE_EQ(parse_quantity("6.25 /mm", Dimension::InverseLength, "k"), 6250);
  EXPECT_DOUBLE_EQ(parse_quantity("1 N/mm", Dimension::Stiffness, "k"), 1000);
  EXPECT_DOUBLE_EQ(parse_quantity("230µm", Dimension::Length, "k"), 230e-6);
  EXPECT_NEAR(parse_quantity("29 psi", Dimension::Pressure, "k"), 0.2e6, 0.001e6);
}

TEST(Units, BareNumberIsOnlyForDimensionless) {
  EXPECT_DOUBLE_EQ(parse_quantity("0.49", Dimension::Dimensionless, "nu"), 0.49);
  EXPECT_THAT([] { parse_quantity("230", Dimension::Length, "needle.length"); },
              testing::ThrowsMessage<InvalidInput>(testing::HasSubstr("needle.length: '230' has no unit")));
}

TEST(Units, RejectsWrongDimensionUnknownUnitAndNaN) {
  EXPECT_THAT([] { parse_quantity("3 GPa", Dimension::Length, "needle.length"); },
              testing::ThrowsMessage<InvalidInput>(testing::HasSubstr("is a pressure")));
  EXPECT_THAT([] { parse_quantity("3 furlong", Dimension::Length, "x"); },
              testing::ThrowsMessage<InvalidInput>(testing::HasSubstr("unknown unit 'furlong'")));
  EXPECT_THROW(parse_quantity("nan um", Dimension::Length, "x"), InvalidInput);
  EXPECT_THROW(parse_quantity("inf um", Dimension::Length, "x"), InvalidInput);
  EXPECT_THROW(parse_quantity("um", Dimension::Length, "x"), InvalidInput);
  EXPECT_THROW(parse_quantity("", Dimension::Length, "x"), InvalidInput);
}

TEST(Units, FormatsBackInTheRequestedUnit) {
  EXPECT_EQ(units::format(230e-6, "um"), "230 um");
  EXPECT_EQ(units::format(5e-5, "mJ"), "0.05 mJ");
}
