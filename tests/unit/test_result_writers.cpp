// JSON and CSV results carry the dissertation's units in their names; files are written whole or not at all.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/result_writers.hpp"

using namespace needlekit;
using testing::HasSubstr;

namespace {

analysis::ArrayDesign table_6_1_cone() {
  analysis::ArrayDesign d;
  d.needle = {needle::Shape::Cone, 30e-6, 150e-6, 0, 500e-6};
  d.material = materials::material_preset("silicon");
  return d;
}

std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST(ResultWriters, PerformanceJsonIsInDissertationUnits) {
  const analysis::ArrayDesign design = table_6_1_cone();
  const auto result = analysis::performance_index(design, {});
  const nlohmann::json json = io::performance_json(design, result);
  // To 12 significant digits (the writers round, so that inputs come back with the user's digits).
  const auto expect_12_digits = [](double json_value, double expected) {
    EXPECT_NEAR(json_value, expected, 5e-12 * std::abs(expected)) << "expected " << expected;
  };
  expect_12_digits(json["tip_area_um2"].get<double>(), result.tip_area * 1e12);
  expect_12_digits(json["deformation_um"].get<double>(), result.deformation * 1e6);
  expect_12_digits(json["performance_index_per_um"].get<double>(), result.performance_index * 1e-6);
  expect_12_digits(json["embedded_volume_um3"].get<double>(), result.embedded_volume * 1e18);
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["shape"], "cone");
  EXPECT_EQ(json["youngs_modulus_GPa"].get<double>(), 169.0);
  EXPECT_EQ(json["width_um"].get<double>(), 1e4);
  for (const char* key : {"Q_um2", "puncture_force_N", "cutting_depth_um", "permeation_depth_um",
                          "critical_buckling_load_N", "buckling_force_N", "critical_bending_load_N",
                          "bending_force_N", "buckling_ok", "bending_ok", "reason", "hole_volume_um3",
                          "gap_volume_um3", "fractional_skin_volume", "pitch_um", "diameter_at_surface_um",
                          "needle_volume_um3", "small_tip_branch", "buckling_method", "tapered_factor_m",
                          "slenderness_ratio", "column_constant", "notes", "material", "needles_per_row"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  // Without an allowable stress the bending check is not assessed: null, not a number.
  analysis::ArrayDesign custom = design;
  custom.material.allowable_stress.reset();
  analysis::InsertionConditions angled;
  angled.angle = 0.1;
  const nlohmann::json unassessed = io::performance_json(custom, analysis::performance_index(custom, angled));
  EXPECT_TRUE(unassessed["critical_bending_load_N"].is_null());
  EXPECT_TRUE(unassessed["bending_ok"].is_null());
}

TEST(ResultWriters, SweepCsvHeaderNamesUnitsAndQuotesReasons) {
  const analysis::SweepResult sweep = analysis::sensitivity_sweep(
      table_6_1_cone(), {}, {}, {analysis::SweepParameter::TipDiameter, 100e-6, 200e-6, 100e-6});
  const std::string csv = io::sweep_csv(sweep);
  std::istringstream lines(csv);
  std::string header, first, second, extra;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(header,
            "tip_diameter_um,performance_index_per_um,status,deformation_um,cutting_depth_um,Q_um2,puncture_force_N,"
            "critical_buckling_load_N,buckling_force_N,reason");
  EXPECT_THAT(first, testing::StartsWith("100,"));
  EXPECT_THAT(second, testing::StartsWith("200,0,constraint_violated,"));
  EXPECT_FALSE(std::getline(lines, extra));
  // A reason with a comma is quoted: 100 deg is outside [0, 90) deg.
  const double degree = M_PI / 180;
  const analysis::SweepResult angles = analysis::sensitivity_sweep(
      table_6_1_cone(), {}, {}, {analysis::SweepParameter::Angle, 0, 100 * degree, 100 * degree});
  const std::string angle_csv = io::sweep_csv(angles);
  EXPECT_THAT(angle_csv, testing::StartsWith("angle_deg,"));
  EXPECT_THAT(angle_csv, HasSubstr("\n100,0,constraint_violated,"));
  EXPECT_THAT(angle_csv, HasSubstr(",\"insertion.angle: 100 deg must be in [0, 90) deg\"\n"));
  EXPECT_EQ(io::sweep_value_column(analysis::SweepParameter::Angle), "angle_deg");
  EXPECT_EQ(io::sweep_value_column(analysis::SweepParameter::NeedlesPerRow), "needles_per_row");
}

TEST(ResultWriters, AtomicWriteReplacesWholeFileOrNothing) {
  const auto dir = fresh_directory("needlekit-writers");
  const auto path = dir / "result.json";
  io::write_text_file_atomically(path, "first");
  io::write_text_file_atomically(path, "second");
  std::ifstream in(path);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), "second");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);

  try {
    io::write_text_file_atomically(dir / "missing" / "result.json", "x");
    ADD_FAILURE() << "no error";
  } catch (const IoError& error) {
    EXPECT_THAT(error.what(), HasSubstr("missing/result.json"));
  }
  try {
    io::write_text_file_atomically(dir, "x");  // a directory cannot be replaced by a file
    ADD_FAILURE() << "no error";
  } catch (const IoError& error) {
    EXPECT_THAT(error.what(), HasSubstr(dir.string()));
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  std::filesystem::remove_all(dir);
}
