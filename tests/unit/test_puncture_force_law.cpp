// Puncture-force laws of the analytic engine (analysis/puncture_force_law.hpp) and their reader ([tissue]
// puncture_force): published values, validity notes, the optimizer's count of extrapolated designs, bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/expect_invalid.hpp"
#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/analysis/puncture_force_law.hpp"
#include "needlekit/io/design_config.hpp"

namespace needlekit {
namespace {

using analysis::PunctureForceLawKind;
constexpr double kPi = 3.14159265358979323846;
double disc(double diameter) { return kPi / 4 * diameter * diameter; }

TEST(PunctureForceLaw, Eq4_2IsTheDissertationsLine) {
  const analysis::PunctureForceLaw law = analysis::eq_4_2_puncture_force_law();
  const double a = disc(95e-6);
  EXPECT_NEAR(analysis::puncture_force(a, law), 0.00019 * (a * 1e12) - 0.66, 1e-12);
  EXPECT_FALSE(analysis::puncture_force_validity_note(a, law).has_value());  // 95 um: inside 71-157 um
  // A 5 um tip: Eq 4.2 gives -0.656 N; the note says so (issue 13).
  const auto note = analysis::puncture_force_validity_note(disc(5e-6), law);
  ASSERT_TRUE(note.has_value());
  EXPECT_NE(note->find("eq-4.2"), std::string::npos);
  EXPECT_NE(note->find("not positive"), std::string::npos);
  EXPECT_NEAR(analysis::puncture_force(disc(5e-6), law), -0.656, 5e-4);
}

TEST(PunctureForceLaw, Romgens2014EndPoints) {
  const analysis::PunctureForceLaw law = analysis::romgens_2014_puncture_force_law();
  EXPECT_NEAR(analysis::puncture_force(disc(5e-6), law), 0.020, 1e-12);
  EXPECT_NEAR(analysis::puncture_force(disc(37e-6), law), 0.167, 1e-12);
  EXPECT_FALSE(analysis::puncture_force_validity_note(disc(20e-6), law).has_value());
  EXPECT_TRUE(analysis::puncture_force_validity_note(disc(70e-6), law).has_value());
  // Rising with the tip, unlike Eq 4.2 below its zero.
  EXPECT_GT(analysis::puncture_force(disc(30e-6), law), analysis::puncture_force(disc(10e-6), law));
}

TEST(PunctureForceLaw, TableInterpolatesInTheEquivalentDiameter) {
  analysis::PunctureForceLaw law = analysis::puncture_force_law_preset(PunctureForceLawKind::Table);
  law.table_tip_diameter = {10e-6, 30e-6};
  law.table_force = {0.01, 0.05};
  EXPECT_NEAR(analysis::puncture_force(disc(20e-6), law), 0.03, 1e-12);
  EXPECT_DOUBLE_EQ(analysis::puncture_force(disc(50e-6), law), 0.05);
  EXPECT_TRUE(analysis::puncture_force_validity_note(disc(50e-6), law).has_value());
  law.table_tip_diameter = {30e-6, 10e-6};
  test::expect_invalid([&] { analysis::validate(law, "tissue.puncture_force"); }, "increasing");
}

TEST(PunctureForceLaw, NamesComeFromOneTable) {
  for (const auto& law : analysis::kPunctureForceLawKindNames) {
    EXPECT_EQ(analysis::puncture_force_law_from_string(law.name, "x"), law.value);
    EXPECT_EQ(analysis::to_string(law.value), law.name);
    EXPECT_NE(analysis::puncture_force_law_names().find(law.name), std::string::npos);
  }
  test::expect_invalid([] { analysis::puncture_force_law_from_string("davis", "tissue.puncture_force"); },
                       "expected one of: \"eq-4.2\"");
}

const char* kDesign = R"([needle]
shape = "cylinder"
tip_diameter = "20 um"
length = "500 um"
material = "silicon"
[array]
needles_per_row = 10
width = "1 cm"
[tissue]
)";

TEST(PunctureForceLawReader, PresetsAndUserLaws) {
  const auto file = [](const std::string& tissue) { return io::parse_design_toml(kDesign + tissue, "d.toml"); };
  EXPECT_EQ(file("").conditions.tissue.force_law.kind, PunctureForceLawKind::Eq4_2);
  EXPECT_EQ(file("puncture_force = \"romgens-2014\"").conditions.tissue.force_law.kind,
            PunctureForceLawKind::Romgens2014);
  const auto linear = file("puncture_force = { law = \"linear-diameter\", slope = \"5000 N/m\", intercept = \"-2 mN\" }")
                          .conditions.tissue.force_law;
  EXPECT_DOUBLE_EQ(linear.slope, 5000);
  EXPECT_DOUBLE_EQ(linear.intercept, -0.002);
  const auto table =
      file("puncture_force = { law = \"table\", tip_diameter = [\"5 um\", \"37 um\"], force = [\"20 mN\", \"167 mN\"] }")
          .conditions.tissue.force_law;
  EXPECT_EQ(table.table_force.size(), 2u);
  // The evaluation names the law and notes the extrapolation.
  const io::DesignFile eq42 = file("");
  const auto r = analysis::performance_index(eq42.design, eq42.conditions, eq42.options);
  EXPECT_EQ(r.puncture_force_law, PunctureForceLawKind::Eq4_2);
  EXPECT_FALSE(r.puncture_force_in_range);
  const io::DesignFile romgens = file("puncture_force = \"romgens-2014\"");
  EXPECT_TRUE(analysis::performance_index(romgens.design, romgens.conditions, romgens.options).puncture_force_in_range);
}

TEST(PunctureForceLawReader, BadInputNamesTheKey) {
  const auto read = [](const std::string& tissue) { io::parse_design_toml(kDesign + tissue, "d.toml"); };
  test::expect_invalid([&] { read("puncture_force = \"linear-area\""); }, "needs its coefficients");
  test::expect_invalid([&] { read("puncture_force = \"davis\""); }, "d.toml:10:");
  test::expect_invalid([&] { read("puncture_force = { law = \"linear-area\", slope = 0.00019, intercept = \"-0.66 N\" }"); },
                       "bare number");
  test::expect_invalid([&] { read("puncture_force = { law = \"romgens-2014\", slope = \"1 N/m\" }"); },
                       "does not apply");
  test::expect_invalid([&] { read("puncture_force = { law = \"table\", tip_diameter = [\"5 um\"], force = [\"1 N\"] }"); },
                       "two or more");
}

}  // namespace
}  // namespace needlekit
