// The JSON text of every result (io/json_text.hpp): a value the user gave comes back as given after a unit
// conversion, at every depth of the document, and nothing but floating-point numbers changes.
#include <gtest/gtest.h>

#include <string>

#include "needlekit/io/json_text.hpp"

using needlekit::io::json_text;
using needlekit::io::rounded_numbers;

TEST(JsonText, UnitConversionsComeBackAsTheUserGaveThem) {
  const double stiffness = 0.2e6 * 1e-6;  // "0.2 N/mm2" read in SI and written back in N/mm^2
  const double depth = 230 * 1e-6 * 1e6;   // "230 um" read in SI and written back in um
  ASSERT_NE(stiffness, 0.2);              // the conversions leave float noise ...
  ASSERT_NE(depth, 230.0);
  const nlohmann::json j = {{"stiffness_N_per_mm2", stiffness},
                            {"steps", {{{"depth_um", depth}, {"force_N", 1.0 / 3.0}}}},
                            {"name", "sharp"},
                            {"count", 7},
                            {"ok", true},
                            {"missing", nullptr}};
  const std::string text = json_text(j);
  EXPECT_NE(text.find("\"stiffness_N_per_mm2\": 0.2\n"), std::string::npos) << text;  // ... which the text drops
  EXPECT_NE(text.find("\"depth_um\": 230.0"), std::string::npos) << text;
  EXPECT_NE(text.find("\"force_N\": 0.333333333333"), std::string::npos) << text;  // 12 significant digits
  EXPECT_EQ(text.back(), '\n');
  const nlohmann::json r = rounded_numbers(j);
  EXPECT_EQ(r["name"], "sharp");
  EXPECT_EQ(r["count"], 7);
  EXPECT_TRUE(r["count"].is_number_integer());
  EXPECT_EQ(r["ok"], true);
  EXPECT_TRUE(r["missing"].is_null());
}
