// Synthetic recovery through the FE (issue 13): an indentation curve and puncture point made by needlekit with known
// E and P_c on one mesh (30 um at the tip, 13k tetrahedra), 2 % noise on every force and on the puncture point,
// fitted from 50 % / 32 % off on another (36 um, 9.1k tetrahedra): both within 3 %, 95 % intervals a few per cent
// wide. The coverage over 20 noise seeds is the benchmark BM_CalibrationCoverage (BENCHMARKS.md, "Calibration").
#include <gtest/gtest.h>

#include <atomic>

#include "../support/calibration_fixture.hpp"

namespace needlekit {
namespace {

TEST(CalibrationRecovery, YoungsModulusAndCriticalPressureThroughTheFe) {
  const test::SyntheticIndentation synthetic = test::synthetic_indentation("calibration_recovery", 30e-6, 7);
  const test::RecoveryOutcome outcome = test::recover(synthetic, 36e-6, 11);
  ASSERT_EQ(outcome.result.status, calibration::CalibrationStatus::Converged) << outcome.result.reason;
  EXPECT_LT(std::abs(outcome.error[0]), 0.03) << "E = " << outcome.result.parameters[0].value;
  EXPECT_LT(std::abs(outcome.error[1]), 0.03) << "P_c = " << outcome.result.parameters[1].value;
  // Intervals: present, a few per cent wide. Whether they hold the truth 95 % of the time is a property of many
  // seeds, measured by BM_CalibrationCoverage (one seed misses in one run of 20 by design).
  for (const auto& p : outcome.result.parameters) {
    ASSERT_TRUE(p.ci95.has_value()) << p.spec.path;
    const double half_width = (p.ci95->second - p.ci95->first) / 2 / p.value;
    EXPECT_GT(half_width, 0.001) << p.spec.path;
    EXPECT_LT(half_width, 0.1) << p.spec.path;
  }
  // The fit reads a 2 % noise level back: the relative residual is about the noise.
  EXPECT_GT(outcome.result.rms_relative, 0.005);
  EXPECT_LT(outcome.result.rms_relative, 0.05);
}

// Without noise the fit misses the truth by the two meshes' own difference (E about 1 % low): the intervals of the
// residuals alone are far too narrow for it; with the estimated discretisation error (the fit re-run on a 0.75×
// finer mesh, discretisation_error.hpp) they hold the truth, and the estimate is of the size of the miss (measured:
// E −1.13 % with an estimated error of 5.4 %, P_c −0.19 % with 2.4 %: Richardson's first-order factor 4 is cautious).
TEST(CalibrationRecovery, IntervalsHoldTheMeshErrorWithoutNoise) {
  const test::SyntheticIndentation synthetic = test::synthetic_indentation("calibration_mesh_error", 30e-6, 7);
  const test::RecoveryOutcome outcome = test::recover(synthetic, 36e-6, 1, 0.0);
  ASSERT_EQ(outcome.result.status, calibration::CalibrationStatus::Converged) << outcome.result.reason;
  const auto& modulus = outcome.result.parameters[0];
  EXPECT_TRUE(outcome.covered[0]) << "E " << outcome.error[0];
  EXPECT_TRUE(outcome.covered[1]) << "P_c " << outcome.error[1];
  EXPECT_GT(modulus.discretisation_error / modulus.value, 0.5 * std::abs(outcome.error[0]));
  EXPECT_LT(modulus.discretisation_error / modulus.value, 10 * std::abs(outcome.error[0]));
}

// A stop request (Ctrl-C in the CLI) ends the FE run it finds at its next Newton iteration, and the fit with it:
// status Stopped, the initial values kept, after one FE run instead of tens, with no exception left to the caller.
TEST(CalibrationRecovery, AStopRequestEndsTheRunningFeRunAndTheFit) {
  const test::SyntheticIndentation synthetic = test::synthetic_indentation("calibration_stop", 30e-6, 7);
  calibration::CalibrationOptions options;
  std::atomic<int> polls{0};
  options.stop_requested = [&] { return ++polls > 3; };  // during the first load step of the first FE run
  int progress_calls = 0;
  options.progress = [&](const calibration::CalibrationProgress&) { return ++progress_calls > 0; };
  const test::RecoveryOutcome outcome = test::recover(synthetic, 36e-6, 11, 0.02, options);
  EXPECT_EQ(outcome.result.status, calibration::CalibrationStatus::Stopped) << outcome.result.reason;
  EXPECT_NE(outcome.result.reason.find("stopped on request during an FE run"), std::string::npos) << outcome.result.reason;
  EXPECT_EQ(progress_calls, 0);  // stopped before the solver's first iteration
  EXPECT_LE(outcome.result.model_runs, 3);  // the initial run; the weight-0 and after-fit runs stop at once
  ASSERT_EQ(outcome.result.parameters.size(), 2u);
  EXPECT_DOUBLE_EQ(outcome.result.parameters[0].value, 0.3e6);  // the initial values
}

}  // namespace
}  // namespace needlekit
