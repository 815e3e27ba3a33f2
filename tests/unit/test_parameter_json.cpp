// The JSON echo of the inputs from the parameter tables alone (io/parameter_json.hpp, issue 38 item 1): one key per
// row under the case file's table, a quantity's key naming its SI unit, a flag as the file writes it, a choice by its
// name; and what `needlekit indent --json` writes under "inputs" is what the case file said.
#include <gtest/gtest.h>

#include <numbers>

#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/insertion/loading_parameters.hpp"
#include "needlekit/insertion/puncture_parameters.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/indentation_output.hpp"
#include "needlekit/io/parameter_json.hpp"
#include "needlekit/mesh/layered_block_parameters.hpp"

namespace needlekit {
namespace {

// The number of values (leaves) of a JSON object, counting into nested objects.
std::size_t leaves(const nlohmann::json& json) {
  if (!json.is_object()) return 1;
  std::size_t count = 0;
  for (const auto& [key, value] : json.items()) count += leaves(value);
  return count;
}

TEST(ParameterJson, EachRowIsOneKeyWithItsUnitUnderItsTable) {
  insertion::Loading loading;
  loading.depth = 230e-6;
  loading.angle = std::numbers::pi / 12;
  loading.steps = 4;
  loading.stop_at_puncture = false;
  nlohmann::json json = nlohmann::json::object();
  io::add_parameters_json(insertion::kLoadingParameters, loading, json);
  EXPECT_EQ(json, nlohmann::json({{"loading",
                                   {{"depth_m", 230e-6},
                                    {"angle_rad", std::numbers::pi / 12},
                                    {"azimuth_rad", 0.0},
                                    {"steps", 4},
                                    {"continue_after_puncture", true}}}}));
  // Every row of every table once.
  const auto rows = [](const auto& table, const auto& options) {
    nlohmann::json echo = nlohmann::json::object();
    io::add_parameters_json(table, options, echo);
    return std::pair{leaves(echo), std::tuple_size_v<std::decay_t<decltype(table)>>};
  };
  for (const auto& [keys, count] : {rows(fem::kSolverParameters, fem::SolverOptions{}),
                                    rows(mesh::kLayeredBlockParameters, mesh::LayeredBlockOptions{}),
                                    rows(insertion::kPunctureParameters, insertion::PunctureOptions{})}) {
    EXPECT_EQ(keys, count);
  }
  EXPECT_EQ(io::detail::unit_suffix(units::Dimension::Area), "_m2");
  EXPECT_EQ(io::detail::unit_suffix(units::Dimension::InverseLength), "_per_m");
  EXPECT_EQ(io::detail::unit_suffix(units::Dimension::Stiffness), "_N_per_m");
  EXPECT_EQ(io::detail::unit_suffix(units::Dimension::Dimensionless), "");
}

TEST(ParameterJson, TheEchoOfACaseIsWhatItsFileSaid) {
  const insertion::IndentationCase c = io::parse_indentation_case_toml(R"(name = "echo"
[needle]
shape = "cone"
tip_diameter = "40 um"
base_diameter = "230 um"
length = "600 um"
[tissue]
preset = "silicone-0.2mpa"
[mesh]
size_at_tip = "25 um"
[loading]
depth = "150 um"
steps = 3
[model]
contact = "surface"
[solver]
friction = 0.3
[puncture]
criterion = "averaged-pressure"
material_length = "40 um"
critical_pressure = "0.5 MPa"
)",
                                                                        "echo.toml");
  const nlohmann::json inputs = io::indentation_inputs_json(c);
  EXPECT_NEAR(inputs["loading"]["depth_m"].get<double>(), 150e-6, 1e-18);
  EXPECT_EQ(inputs["loading"]["steps"], 3);
  EXPECT_EQ(inputs["model"]["contact"], "surface");
  EXPECT_EQ(inputs["solver"]["friction"], 0.3);
  EXPECT_NEAR(inputs["mesh"]["size_at_tip_m"].get<double>(), 25e-6, 1e-18);
  EXPECT_EQ(inputs["puncture"]["criterion"], "averaged-pressure");
  EXPECT_NEAR(inputs["puncture"]["material_length_m"].get<double>(), 40e-6, 1e-18);
  EXPECT_EQ(inputs["puncture"]["critical_pressure_Pa"], 0.5e6);  // an optional quantity given
  EXPECT_TRUE(inputs["puncture"]["toughness_N_per_m"].is_null());  // and one not given
}

}  // namespace
}  // namespace needlekit
