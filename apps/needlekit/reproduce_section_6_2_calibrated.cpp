// §6.2 of `needlekit reproduce`, after calibration (issue 13): the phantom's E and P_c fitted to the sharp bevel's
// experiment alone (examples/calibrate_6_2_phantom.toml), then the blunt bevel and the cylinder predicted with the
// fitted values (weight-0 experiments of the same file), beside the uncalibrated rows. Only with
// --with-calibration and not with --quick: the fit is some tens of FE runs. What the prediction can and cannot claim: docs/calibration.md.
#include <fmt/format.h>

#include "needlekit/calibration/calibrate.hpp"
#include "needlekit/calibration/calibration_output.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/json_text.hpp"
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {

void calibrated_phantom(const RunContext& context, SectionReport& report, const SectionProgress& progress) {
  const char* example = "calibrate_6_2_phantom.toml";
  if (context.quick || !context.with_calibration) {
    report.input(fmt::format("examples/{}: the §6.2 prediction after calibration runs with `reproduce "
                             "--with-calibration` (full run only: a fit of some tens of FE runs)",
                             example));
    return;
  }
  progress(0.5, "calibration on the sharp bevel");
  const calibration::CalibrationProblem problem = calibration::read_calibration_file(context.example(example));
  calibration::CalibrationOptions options;
  options.progress = [&](const calibration::CalibrationProgress&) {
    context.check_interrupt();
    return true;
  };
  options.stop_requested = [] { return interrupt_requested(); };  // Ctrl-C inside an FE run, not after it
  const calibration::CalibrationResult result = calibration::calibrate(problem, options);
  context.check_interrupt();
  const std::string json = context.write("section_6_2/calibration_6_2.json",
                                         io::json_text(calibration::calibration_json(problem, result)));
  report.data_file(json);
  std::string fitted;
  for (const calibration::FittedParameter& p : result.parameters)
    fitted += fmt::format("{}{} = {}", fitted.empty() ? "" : ", ", p.spec.path, calibration::as_given(p.spec, p.value));
  report.input(fmt::format("examples/{}: fitted on the sharp bevel's puncture point and its quadratic pre-puncture "
                           "rise: {} ({}, {} iterations, rms {:.3g})",
                           example, fitted, calibration::to_string(result.status), result.iterations,
                           result.rms_relative));
  const PublishedValues& published = *context.published;
  for (const calibration::ExperimentFit& fit : result.experiments) {
    const auto& p = fit.prediction.puncture;
    const std::string what = fit.predicted_only ? "predicted after calibration" : "fitted";
    if (fit.name.rfind("cylinder", 0) == 0) {
      report.input(fmt::format("cylinder, {}: {} (experiment: no puncture within 2 mm)", what,
                               p ? fmt::format("punctures at {:.4g} mm, {:.4g} N", p->depth * 1e3, p->force)
                                 : "no puncture within the simulated 2 mm"));
      continue;
    }
    const std::string key = fit.name.rfind("sharp", 0) == 0 ? "sharp_bevel" : "blunt_bevel";
    const std::string label = key == "sharp_bevel" ? "sharp bevel" : "blunt bevel";
    if (!p) {
      report.input(fmt::format("{}, {}: no puncture within the simulated depth", label, what));
      continue;
    }
    report.compare(published.at(fmt::format("6.2.{}.puncture_depth", key)), p->depth * 1e3,
                   fmt::format("{}: puncture depth, {}", label, what), "E and P_c calibrated on the sharp bevel");
    report.compare(published.at(fmt::format("6.2.{}.puncture_force", key)), p->force,
                   fmt::format("{}: puncture force, {}", label, what), "E and P_c calibrated on the sharp bevel");
  }
  report.deviation("The calibrated rows fit E and P_c to the sharp bevel's experiment; the blunt bevel and the cylinder "
                   "are predictions with no further fitting (docs/calibration.md says what they can claim).");
  progress(0.5, "calibration done");
}

}  // namespace needlekit::cli::reproduce
