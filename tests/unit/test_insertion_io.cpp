// Reading measured force curves and insertion case settings, and writing the insertion curve: units from the
// headers, errors that name the file, line and column or key, markers at the puncture.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "needlekit/core/errors.hpp"
#include "../support/expect_invalid.hpp"
#include "needlekit/io/force_curve_csv.hpp"
#include "needlekit/io/insertion_case.hpp"
#include "needlekit/io/insertion_output.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

using namespace needlekit;
using testing::HasSubstr;
using needlekit::test::expect_invalid;

namespace {

TEST(ForceCurveCsv, ReadsUnitsFromTheHeaderInAnyColumnOrder) {
  const auto curve =
      io::parse_force_curve_csv("# measured\ntime_s,force_mN,depth_mm\n0,0,0\n1,2.5,0.1\n\n2,4,0.25\n", "m.csv");
  ASSERT_EQ(curve.depth.size(), 3u);
  EXPECT_DOUBLE_EQ(curve.depth[2], 0.25e-3);
  EXPECT_DOUBLE_EQ(curve.force[1], 2.5e-3);
}

TEST(ForceCurveCsv, BadCurvesNameFileLineAndColumn) {
  expect_invalid([] { io::parse_force_curve_csv("depth_um,load\n1,2\n", "m.csv"); },
                 "m.csv:1: missing column force_<unit>");
  expect_invalid([] { io::parse_force_curve_csv("force_N\n1\n", "m.csv"); }, "missing column depth_<unit>");
  expect_invalid([] { io::parse_force_curve_csv("depth_um,force_N\n1,0.1\n3,0.2\n2,0.3\n", "m.csv"); },
                 "m.csv:4: depth is not monotonic");
  expect_invalid([] { io::parse_force_curve_csv("depth_um,force_N\n1,abc\n", "m.csv"); }, "m.csv:2: column 2");
  expect_invalid([] { io::parse_force_curve_csv("depth_furlong,force_N\n1,1\n", "m.csv"); }, "depth_furlong");
  expect_invalid([] { io::parse_force_curve_csv("depth_um,force_N\n", "m.csv"); }, "no samples");
}

const char* kSettings = R"(name = "x"
[needle]
shape = "cone"
[post_puncture]
stiffness = "0.2 N/mm2"
scale = 0.168
final_depth = "1 mm"
side_tolerance = "2 deg"
[loading]
depth = "100 um"
)";

TEST(InsertionSettings, ReadsThePostPunctureTableAndBlanksItForTheIndentationReader) {
  const auto settings = io::parse_insertion_settings(kSettings, "case.toml");
  EXPECT_DOUBLE_EQ(settings.model.stiffness, 0.2e6);
  EXPECT_DOUBLE_EQ(settings.model.scale, 0.168);
  EXPECT_DOUBLE_EQ(settings.curve.final_depth, 1e-3);
  EXPECT_NEAR(settings.classification.side_tolerance, 2 * 3.14159265358979 / 180, 1e-12);
  EXPECT_EQ(settings.indentation_text.find("post_puncture"), std::string::npos);
  EXPECT_EQ(settings.indentation_text.find("stiffness"), std::string::npos);
  EXPECT_NE(settings.indentation_text.find("[loading]"), std::string::npos);
  // Line numbers are kept: [loading] is still on line 9.
  std::size_t line = 1, at = settings.indentation_text.find("[loading]");
  for (std::size_t i = 0; i < at; ++i) line += settings.indentation_text[i] == '\n';
  EXPECT_EQ(line, 9u);
}

TEST(InsertionSettings, BadSettingsNameTheKey) {
  expect_invalid([] { io::parse_insertion_settings("[needle]\n", "c.toml"); }, "missing table [post_puncture]");
  expect_invalid(
      [] { io::parse_insertion_settings("[post_puncture]\nstiffness = 0.2\nscale = 1\nfinal_depth = \"1 mm\"\n", "c.toml"); },
      "c.toml:2: key 'post_puncture.stiffness'");
  expect_invalid(
      [] {
        io::parse_insertion_settings(
            "[post_puncture]\nstiffness = \"0.2 MPa\"\nscale = 1\nfinal_depth = \"1 mm\"\nstifness = 1\n", "c.toml");
      },
      "unknown key 'post_puncture.stifness'");
  expect_invalid(
      [] { io::parse_insertion_settings("[post_puncture]\nstiffness = \"0.2 MPa\"\nscale = 0\nfinal_depth = \"1 mm\"\n", "c.toml"); },
      "post_puncture.scale");
  expect_invalid(
      [] { io::parse_insertion_settings("[post_puncture]\nstiffness = \"0.2 MPa\"\nscale = 1\n", "c.toml"); },
      "post_puncture.final_depth");
}

TEST(InsertionOutput, CsvAndJsonMarkThePunctureAndTheRelaxedSample) {
  const auto mesh = needle::needle_surface_mesh({needle::Shape::Cylinder, 230e-6, 230e-6, 0, 1000e-6}, {32, 2});
  const auto loads = insertion::post_puncture_loads(mesh);
  insertion::NeedleInsertion needle;
  needle.pre_puncture.curve = {{100e-6, 200e-6}, {0.01, 0.03}};
  needle.pre_puncture.puncture = insertion::PuncturePoint{200e-6, 0.03, insertion::PunctureCriterion::CriticalPressure};
  needle.loads = &loads;
  const auto curve = insertion::insertion_curve({needle}, {400e-6, 2});
  const std::string csv = io::insertion_curve_csv(curve);
  EXPECT_THAT(csv, HasSubstr("depth_um,force_N,phase,punctured_needles,marker\n0,0,indentation,0,\n"));
  EXPECT_THAT(csv, HasSubstr("200,0.03,indentation,0,puncture\n200,"));
  EXPECT_THAT(csv, HasSubstr(",cutting,1,relaxed\n300,"));
  const auto json = io::insertion_curve_json(curve);
  EXPECT_DOUBLE_EQ(json["puncture_depth_um"].get<double>(), 200);
  EXPECT_DOUBLE_EQ(json["puncture_force_N"].get<double>(), 0.03);
  const double after = insertion::post_puncture_force(loads, 200e-6, 0.2e6, 0.168);
  EXPECT_NEAR(json["relaxation_drop_N"].get<double>(), 0.03 - after, 1e-15);
  EXPECT_EQ(json["phase"].back(), "cutting");
  EXPECT_EQ(json["depth_um"].size(), json["force_N"].size());
}

}  // namespace
