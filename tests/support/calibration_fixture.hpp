// Synthetic FE calibration data for the recovery test and the coverage benchmark: an indentation case (a flat
// 300 um punch, 120 um into a 1 mm silicone layer, E = 0.2 MPa, nu = 0.3, P_c = 0.1 MPa) run once on a "truth" mesh; its
// curve and puncture point with multiplicative Gaussian noise; the fit of E and P_c on another mesh. The punch is
// wide against the mesh (a / h = 4-5) and the depth moderate (d / a = 0.8), so that meshes of 30, 40 and 50 um give
// forces within 0.7 % of each other: the fit then measures the calibration, not the mesh (docs/calibration.md).
#pragma once
#include <fmt/format.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "needlekit/calibration/calibrate.hpp"

namespace needlekit::test {

inline constexpr double kTrueModulus = 0.2e6;             // Pa, the punch's and the bevel benchmark's phantom
inline constexpr double kTrueCriticalPressure = 0.663e6;  // Pa, the bevel benchmark's phantom (bench_calibration.cpp)
inline constexpr double kPunchCriticalPressure = 0.1e6;   // Pa, the punch: punctures at about 90 of its 120 um

inline std::string punch_case(double size_at_tip) {
  return fmt::format(R"(name = "punch"
[needle]
shape = "cylinder"
tip_diameter = "300 um"
length = "500 um"
segments = 48
axial_segments = 2
[tissue]
width = "2000 um"
length = "2000 um"
[[tissue.layers]]
name = "silicone"
thickness = "1000 um"
youngs_modulus = "0.2 MPa"
poisson_ratio = 0.3
[mesh]
size_at_tip = "{:g} um"
size_far = "400 um"
refinement_radius = "250 um"
[loading]
depth = "120 um"
steps = 8
[model]
law = "neo-hookean"
contact = "tip-nodes"
[puncture]
critical_pressure = "0.1 MPa"
)",
                     size_at_tip * 1e6);
}

// E from 0.3 MPa (50 % off) and P_c from `pressure`, within wide bounds.
inline std::string modulus_and_pressure(double pressure_mpa, double lower_mpa, double upper_mpa) {
  return fmt::format(R"([[parameters]]
path = "tissue.layers.0.youngs_modulus"
initial = "0.3 MPa"
bounds = ["0.02 MPa", "5 MPa"]
[[parameters]]
path = "puncture.critical_pressure"
initial = "{:g} MPa"
bounds = ["{:g} MPa", "{:g} MPa"]
)",
                     pressure_mpa, lower_mpa, upper_mpa);
}
// The punch's P_c from 32 % off; the phantom's (the bevel benchmark) likewise.
inline std::string punch_parameters() { return modulus_and_pressure(0.068, 0.01, 1); }
inline std::string phantom_parameters() { return modulus_and_pressure(0.45, 0.05, 10); }

struct SyntheticIndentation {
  std::filesystem::path dir;
  insertion::ForceDepthCurve curve;       // noise-free, truth mesh
  insertion::PuncturePoint puncture;      // noise-free
};

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline SyntheticIndentation synthetic_indentation(const std::string& name, double truth_size, unsigned) {
  SyntheticIndentation s;
  s.dir = std::filesystem::temp_directory_path() / ("needlekit_" + name);
  std::filesystem::remove_all(s.dir);
  std::filesystem::create_directories(s.dir);
  std::ofstream(s.dir / "truth.toml") << punch_case(truth_size);
  calibration::ExperimentSpec spec;
  spec.name = "truth";
  spec.case_path = s.dir / "truth.toml";
  spec.case_text = read_file(spec.case_path);
  spec.kind = calibration::ExperimentKind::Indentation;
  spec.puncture.force = 1;
  const calibration::ParameterSpec e{"tissue.layers.0.youngs_modulus", units::Dimension::Pressure, "MPa",
                                     kTrueModulus, 1e4, 1e7, "truth"};
  const calibration::ExperimentModel truth(spec, {e});
  const calibration::Prediction p = truth.predict({kTrueModulus});
  s.curve = p.curve;
  if (p.puncture) s.puncture = *p.puncture;
  return s;
}

struct RecoveryOutcome {
  calibration::CalibrationResult result;
  std::array<double, 2> error{};    // relative errors of E and P_c
  std::array<bool, 2> covered{};    // the 95 % interval holds the truth
};

// Writes the noisy data (2 % on every force and on the puncture point) and fits E and P_c on a mesh of `fit_size`.
inline RecoveryOutcome recover(const SyntheticIndentation& s, double fit_size, unsigned seed, double noise = 0.02,
                               const calibration::CalibrationOptions& options = {}) {
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  std::string csv = "depth_um,force_N\n";
  for (std::size_t i = 1; i < s.curve.depth.size(); ++i)
    csv += fmt::format("{:.9g},{:.9g}\n", s.curve.depth[i] * 1e6, s.curve.force[i] * (1 + gauss(random)));
  const std::string tag = fmt::format("{}", seed);
  std::ofstream(s.dir / ("measured_" + tag + ".csv")) << csv;
  std::ofstream(s.dir / "fit_case.toml") << punch_case(fit_size);
  std::ofstream(s.dir / ("fit_" + tag + ".toml")) << fmt::format(
      R"({}[[experiments]]
name = "punch"
case = "fit_case.toml"
measured = "measured_{}.csv"
puncture = {{ depth = "{:.9g} um", force = "{:.9g} N" }}
)",
      punch_parameters(), tag, s.puncture.depth * 1e6 * (1 + gauss(random)), s.puncture.force * (1 + gauss(random)));
  RecoveryOutcome outcome;
  outcome.result =
      calibration::calibrate(calibration::read_calibration_file(s.dir / ("fit_" + tag + ".toml")), options);
  const std::array<double, 2> truth{kTrueModulus, kPunchCriticalPressure};
  for (std::size_t j = 0; j < 2 && j < outcome.result.parameters.size(); ++j) {
    const auto& p = outcome.result.parameters[j];
    outcome.error[j] = p.value / truth[j] - 1;
    outcome.covered[j] = p.ci95 && p.ci95->first <= truth[j] && truth[j] <= p.ci95->second;
  }
  return outcome;
}

}  // namespace needlekit::test
