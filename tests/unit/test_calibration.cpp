// Calibration (calibration/*.hpp): case-file paths, the analytic model's exact answers (alpha, tau and a puncture-
// force law recovered from noise-free synthetic data to 1e-6), K and S reported as degenerate, and bad input named
// by file and key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iterator>

#include "../support/expect_invalid.hpp"
#include "needlekit/calibration/parameter_statistics.hpp"
#include "needlekit/calibration/calibrate.hpp"
#include "needlekit/calibration/calibration_solver_parameters.hpp"
#include "needlekit/calibration/case_parameters.hpp"
#include "needlekit/io/design_config.hpp"
#include "../support/scratch_files.hpp"

namespace needlekit {
namespace {

using calibration::CalibrationStatus;

TEST(CaseParameters, ReadAndReplaceKeepTheRestOfTheText) {
  const std::string text = "# c\n[[tissue.layers]]\nyoungs_modulus = \"0.2 MPa\"  # E\npoisson_ratio = 0.49\n"
                           "[post_puncture]\nscale = 0.168\n";
  const auto e = calibration::case_value(text, "tissue.layers.0.youngs_modulus", "c.toml");
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->dimension, units::Dimension::Pressure);
  EXPECT_DOUBLE_EQ(e->value, 2e5);
  EXPECT_EQ(e->line, 3);
  EXPECT_FALSE(calibration::case_value(text, "tissue.layers.1.youngs_modulus", "c.toml").has_value());
  const std::string edited =
      calibration::with_case_value(text, "tissue.layers.0.youngs_modulus", 2.5e5, units::Dimension::Pressure, "MPa", 6);
  EXPECT_EQ(edited, "# c\n[[tissue.layers]]\nyoungs_modulus = \"0.25 MPa\"  # E\npoisson_ratio = 0.49\n"
                    "[post_puncture]\nscale = 0.168\n");
  const std::string scaled = calibration::with_case_value(text, "post_puncture.scale", 2, units::Dimension::Dimensionless);
  EXPECT_DOUBLE_EQ(calibration::case_value(scaled, "post_puncture.scale", "c.toml")->value, 2.0);
  EXPECT_NE(calibration::parameter_kind_of("tissue.layers.3.youngs_modulus"), nullptr);
  EXPECT_EQ(calibration::parameter_kind_of("needle.length"), nullptr);
}

// A cylinder design file with the analytic tissue model written out (so that alpha and tau can be fitted).
std::string design(double tip_um, const std::string& law = "") {
  return fmt::format(R"([needle]
shape = "cylinder"
tip_diameter = "{} um"
length = "600 um"
material = "silicon"
[array]
needles_per_row = 10
width = "1 cm"
[tissue]
model = {{ alpha = "0.0183 N", tau = "6.25 /mm" }}
{}
)",
                     tip_um, law);
}

struct Synthetic {
  std::filesystem::path dir;
  std::string experiments;
};

// Design files for several tips and their d and F(A) from the library at the true values.
Synthetic synthetic_designs(const std::string& name, const std::vector<double>& tips_um, const std::string& true_law,
                            const std::string& fitted_law, bool with_depth, bool with_force) {
  Synthetic s{test::scratch_directory(name), ""};
  for (double tip : tips_um) {
    const io::DesignFile truth = io::parse_design_toml(design(tip, true_law), "truth.toml");
    const auto r = analysis::performance_index(truth.design, truth.conditions, truth.options);
    const std::string file = fmt::format("tip_{}.toml", tip);
    test::write_text(s.dir / file, design(tip, fitted_law));
    s.experiments += fmt::format("[[experiments]]\nname = \"tip {} um\"\ncase = \"{}\"\npuncture = {{ {}{}{} }}\n\n",
                                 tip, file, with_depth ? fmt::format("depth = \"{:.17g} um\"", r.deformation * 1e6) : "",
                                 with_depth && with_force ? ", " : "",
                                 with_force ? fmt::format("force = \"{:.17g} N\"", r.puncture_force) : "");
  }
  return s;
}

// alpha and tau of Eq 4.1 from 0.03 N and 4 /mm.
constexpr const char* kAlphaAndTau = R"([[parameters]]
path = "tissue.model.alpha"
initial = "0.03 N"
bounds = ["0.001 N", "0.1 N"]
[[parameters]]
path = "tissue.model.tau"
initial = "4 /mm"
bounds = ["1 /mm", "20 /mm"]
)";

TEST(Calibration, AlphaAndTauFromSyntheticAreaDepthDataExactly) {
  // Truth: the skin model (alpha = 0.0183 N, tau = 6.25 /mm); tips 80-150 um (F(A) > alpha: Eq 4.3's branch).
  Synthetic s = synthetic_designs("calibration_alpha_tau", {80, 100, 120, 150}, "", "", true, false);
  test::write_text(s.dir / "fit.toml", std::string(kAlphaAndTau) + s.experiments);
  const auto problem = calibration::read_calibration_file(s.dir / "fit.toml");
  const auto result = calibration::calibrate(problem);
  ASSERT_EQ(result.status, CalibrationStatus::Converged) << result.reason;
  EXPECT_NEAR(result.parameters[0].value / 0.0183, 1, 1e-6);
  EXPECT_NEAR(result.parameters[1].value / 6250.0, 1, 1e-6);
  EXPECT_LT(result.rms_relative, 1e-7);
  EXPECT_EQ(result.parameters[0].spec.unit, "N");
  EXPECT_EQ(result.model_runs, 0);  // analytic: no FE
}

TEST(Calibration, AProgressCallbackThatAnswersFalseStopsTheFitAndKeepsTheBestPoint) {
  Synthetic s = synthetic_designs("calibration_stopped", {80, 100, 120, 150}, "", "", true, false);
  test::write_text(s.dir / "fit.toml", std::string(kAlphaAndTau) + s.experiments);
  const auto problem = calibration::read_calibration_file(s.dir / "fit.toml");
  calibration::CalibrationOptions options;
  int calls = 0;
  options.progress = [&](const calibration::CalibrationProgress& p) {
    ++calls;
    return p.iteration < 2;  // stop after the second iteration
  };
  const auto result = calibration::calibrate(problem, options);
  EXPECT_EQ(result.status, CalibrationStatus::Stopped) << result.reason;
  EXPECT_EQ(calls, 3);  // iterations 0, 1, 2
  EXPECT_EQ(result.iterations, 2);
  EXPECT_NE(result.reason.find("stopped on request"), std::string::npos) << result.reason;
  // The point kept is the solver's current one: better than the initial values, not yet the optimum.
  EXPECT_LT(std::abs(result.parameters[0].value / 0.0183 - 1), std::abs(0.03 / 0.0183 - 1));
}

TEST(Calibration, PunctureForceLawCoefficientsFromSeveralNeedles) {
  // Truth: Romgens et al. 2014's line; the fit starts from another linear-diameter law.
  Synthetic s = synthetic_designs(
      "calibration_law", {5, 12, 20, 37}, "puncture_force = \"romgens-2014\"",
      "puncture_force = { law = \"linear-diameter\", slope = \"3000 N/m\", intercept = \"0.01 N\" }", false, true);
  test::write_text(s.dir / "fit.toml", R"([[parameters]]
path = "tissue.puncture_force.slope"
initial = "3000 N/m"
bounds = ["100 N/m", "1e5 N/m"]
[[parameters]]
path = "tissue.puncture_force.intercept"
initial = "0.01 N"
bounds = ["-0.1 N", "0.1 N"]
)" + s.experiments);
  const auto result = calibration::calibrate(calibration::read_calibration_file(s.dir / "fit.toml"));
  ASSERT_EQ(result.status, CalibrationStatus::Converged) << result.reason;
  const auto romgens = analysis::romgens_2014_puncture_force_law();
  EXPECT_NEAR(result.parameters[0].value / romgens.slope, 1, 1e-6);
  EXPECT_NEAR(result.parameters[1].value / romgens.intercept, 1, 1e-6);
}

// An insert case with a given pre-puncture curve (no FE): the cutting force depends on K*S only.
std::filesystem::path insert_case(const std::filesystem::path& dir) {
  test::write_text(dir / "pre.csv", "depth_um,force_N\n0,0\n60,0.002\n120,0.008\n");
  test::write_text(dir / "insert.toml", R"(name = "bevel"
[needle]
shape = "bevel"
tip_diameter = "10 um"
base_diameter = "230 um"
length = "1000 um"
[tissue]
preset = "silicone-0.2mpa"
[loading]
depth = "300 um"
[puncture]
critical_pressure = "0.663 MPa"
[post_puncture]
stiffness = "0.2 N/mm2"
scale = 0.168
final_depth = "1000 um"
samples = 40
[pre_puncture]
curve = "pre.csv"
)");
  return dir / "insert.toml";
}

TEST(Calibration, StiffnessAndScaleTogetherAreDegenerate) {
  const auto dir = test::scratch_directory("calibration_ks");
  insert_case(dir);
  // The measured curve: the model's own at K = 0.2 N/mm2, S = 0.5.
  calibration::ExperimentSpec spec;
  spec.name = "truth";
  spec.case_path = dir / "insert.toml";
  spec.case_text = R"()";
  {
    std::ifstream in(dir / "insert.toml");
    spec.case_text.assign(std::istreambuf_iterator<char>(in), {});
  }
  spec.kind = calibration::ExperimentKind::Insertion;
  spec.puncture.force = 0.008;
  calibration::ParameterSpec scale{"post_puncture.scale", units::Dimension::Dimensionless, "", 0.5, 0.01, 10, "x"};
  const calibration::ExperimentModel truth(spec, {scale});
  const auto curve = truth.predict({0.5}).curve;
  std::string csv = "depth_um,force_N\n";
  for (std::size_t i = 0; i < curve.depth.size(); ++i)
    if (curve.depth[i] > 200e-6 && (i == 0 || curve.depth[i] > curve.depth[i - 1]))
      csv += fmt::format("{:.17g},{:.17g}\n", curve.depth[i] * 1e6, curve.force[i]);
  test::write_text(dir / "cutting.csv", csv);
  test::write_text(dir / "fit.toml", R"([[parameters]]
path = "post_puncture.stiffness"
initial = "0.3 N/mm2"
bounds = ["0.01 N/mm2", "10 N/mm2"]
[[parameters]]
path = "post_puncture.scale"
initial = 0.2
bounds = [0.01, 10]
[[experiments]]
name = "cutting"
case = "insert.toml"
measured = "cutting.csv"
)");
  const auto result = calibration::calibrate(calibration::read_calibration_file(dir / "fit.toml"));
  EXPECT_NE(result.status, CalibrationStatus::Failed) << result.reason;
  EXPECT_NEAR(result.parameters[0].value * result.parameters[1].value / (0.2e6 * 0.5), 1, 1e-5);  // K*S is found
  bool degenerate = false;
  for (const std::string& w : result.warnings)
    degenerate = degenerate || (w.find("degenerate") != std::string::npos &&
                                w.find("post_puncture.stiffness and post_puncture.scale") != std::string::npos);
  EXPECT_TRUE(degenerate);
  EXPECT_FALSE(result.parameters[0].ci95.has_value());
  EXPECT_FALSE(result.parameters[1].ci95.has_value());
}

TEST(CalibrationBadInput, NamesFileAndKey) {
  const auto dir = test::scratch_directory("calibration_bad");
  test::write_text(dir / "d.toml", design(100));
  const std::string parameter = "[[parameters]]\npath = \"tissue.model.alpha\"\ninitial = \"0.02 N\"\n"
                                "bounds = [\"0.001 N\", \"0.1 N\"]\n";
  const std::string experiment = "[[experiments]]\ncase = \"d.toml\"\npuncture = { depth = \"100 um\" }\n";
  const auto fails = [&](const std::string& text, const std::string& fragment) {
    test::write_text(dir / "c.toml", text);
    test::expect_invalid([&] { calibration::calibrate(calibration::read_calibration_file(dir / "c.toml")); }, fragment);
  };
  fails("[[parameters]]\npath = \"tissue.model.alpha\"\ninitial = \"0.2 N\"\nbounds = [\"0.001 N\", \"0.1 N\"]\n" +
            experiment,
        "c.toml:3: key 'parameters[0].initial': lies outside bounds");
  fails("[[parameters]]\npath = \"tissue.layers.0.youngs_modulus\"\ninitial = \"0.2 MPa\"\n"
        "bounds = [\"0.01 MPa\", \"1 MPa\"]\n" + experiment,
        "does not exist in the case");
  fails("[[parameters]]\npath = \"needle.length\"\ninitial = \"1 mm\"\nbounds = [\"0.1 mm\", \"2 mm\"]\n" + experiment,
        "not a calibratable key");
  // The puncture force F(A) does not depend on alpha: no experiment depends on the parameter.
  fails(parameter + "[[experiments]]\ncase = \"d.toml\"\npuncture = { force = \"0.5 N\" }\n",
        "no experiment depends on 'tissue.model.alpha'");
  fails(parameter + "[[experiments]]\ncase = \"d.toml\"\nmeasured = \"curve.csv\"\n",
        "c.toml:7: key 'experiments[0].measured': a force-depth curve does not apply to a design file");
  test::write_text(dir / "pre.csv", "depth_um,force_N\n0,0\n10,1\n");
  insert_case(dir);
  const std::string insert_parameter = "[[parameters]]\npath = \"post_puncture.scale\"\ninitial = 0.2\nbounds = [0.01, 1]\n";
  test::write_text(dir / "m.csv", "depth_um,force_N\n300,0.01\n200,0.02\n400,0.03\n");
  fails(insert_parameter + "[[experiments]]\ncase = \"insert.toml\"\nmeasured = \"m.csv\"\n", "m.csv:3");
  test::write_text(dir / "m.csv", "depth_um,force_N\n300,0.01\n400,0.03\n");
  fails(insert_parameter + "[[experiments]]\ncase = \"insert.toml\"\nmeasured = \"m.csv\"\n", "expected at least 3");
  test::write_text(dir / "m.csv", "depth_um,f\n300,0.01\n400,0.03\n500,0.04\n");
  fails(insert_parameter + "[[experiments]]\ncase = \"insert.toml\"\nmeasured = \"m.csv\"\n", "force_");
}

// [solver] is read from calibration::kCalibrationSolverParameters: every key of the table reads back, relative_step = 0
// (automatic, the default) is accepted, a value outside a row's range names the key and the range, and calibrate()
// checks the settings Python may set.
TEST(CalibrationSolverTable, EveryKeyReadsBackAndAValueOutsideItsRangeNamesTheRange) {
  const auto dir = test::scratch_directory("calibration_solver_table");
  test::write_text(dir / "d.toml", design(100));
  const std::string rest = "[[parameters]]\npath = \"tissue.model.alpha\"\ninitial = \"0.02 N\"\n"
                           "bounds = [\"0.001 N\", \"0.1 N\"]\n"
                           "[[experiments]]\ncase = \"d.toml\"\npuncture = { depth = \"100 um\" }\n";
  const auto read = [&](const std::string& solver) {
    test::write_text(dir / "c.toml", "[solver]\n" + solver + rest);
    return calibration::read_calibration_file(dir / "c.toml");
  };
  const calibration::SolverSettings given =
      read("max_iterations = 7\nrelative_step = 0\nfunction_tolerance = 1e-8\nparameter_tolerance = 1e-9\n"
           "mesh_error = false\nmesh_error_refinement = 0.5\n")
          .solver;
  EXPECT_EQ(given.max_iterations, 7);
  EXPECT_EQ(given.relative_step, 0.0);
  EXPECT_EQ(given.function_tolerance, 1e-8);
  EXPECT_EQ(given.parameter_tolerance, 1e-9);
  EXPECT_FALSE(given.mesh_error);
  EXPECT_EQ(given.mesh_error_refinement, 0.5);
  std::vector<std::string_view> keys;
  for_each_parameter(calibration::kCalibrationSolverParameters, [&](const auto& row) { keys.push_back(row.key); });
  EXPECT_EQ(keys, (std::vector<std::string_view>{"max_iterations", "relative_step", "function_tolerance",
                                                  "parameter_tolerance", "mesh_error", "mesh_error_refinement"}));
  test::expect_invalid([&] { read("max_iterations = 0\n"); },
                       "c.toml:2: key 'solver.max_iterations': 0 is out of range, expected an integer >= 1");
  test::expect_invalid([&] { read("relative_step = 0.1\n"); },
                       "key 'solver.relative_step': 0.1 is out of range, expected a number in [0, 0.1)");
  test::expect_invalid([&] { read("tolerance = 0.1\n"); }, "unknown key 'solver.tolerance'");
  calibration::CalibrationProblem problem = read("");
  problem.solver.function_tolerance = 2;
  test::expect_invalid([&] { calibration::calibrate(problem); },
                       "calibration solver function_tolerance = 2: expected in (0, 1)");
}

}  // namespace
}  // namespace needlekit

// A parameter the residuals barely depend on (the §6.2 phantom's P_c once the criterion never fires) is identifiable
// by the singular values of the scaled Jacobian, but its interval is wider than its value: a warning says so.
TEST(ParameterStatistics, AnIntervalWiderThanTheValueIsReported) {
  Eigen::MatrixXd jacobian(4, 2);
  jacobian << 1, 1e-3, 1, -1e-3, 1, 1e-3, 1, -1e-3;
  Eigen::VectorXd residuals(4);
  residuals << 0.1, -0.1, 0.1, -0.1;
  const needlekit::calibration::ParameterStatistics s =
      needlekit::calibration::parameter_statistics(jacobian, residuals, {1.0, 1.0}, {"a", "b"});
  ASSERT_TRUE(s.ci95[0] && s.ci95[1]);
  EXPECT_NEAR(s.standard_error[1], std::sqrt(0.02 / 4e-6), 1e-9);  // s^2 = 0.04 / (4 - 2), |J_b|^2 = 4e-6
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_THAT(s.warnings[0], testing::HasSubstr("b: hardly determined by the data: its 95 % interval"));
}
