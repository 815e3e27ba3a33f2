// §6.2 of `needlekit reproduce`, after calibration (issue 13): the phantom's E and P_c fitted to the sharp bevel's
// experiment alone (examples/calibrate_6_2_phantom.toml), then the blunt bevel and the cylinder predicted with the
// fitted values (weight-0 experiments of the same file), beside the uncalibrated rows. Only with
// --with-calibration and not with --quick: the fit is some tens of FE runs. What the prediction can and cannot claim: docs/calibration.md.
#include <fmt/format.h>

#include <algorithm>

#include "needlekit/calibration/calibrate.hpp"
#include "needlekit/calibration/calibration_output.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/json_text.hpp"
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {

namespace {

// One experiment's fit or prediction against the experiment: the puncture point (the bevels), the force at the
// experiment's puncture depth when the model went past it without puncturing, or what the run can claim (the
// cylinder: no puncture within 2 mm).
void compare_experiment(const PublishedValues& published, SectionReport& report,
                        const calibration::ExperimentFit& fit) {
  const calibration::Prediction& prediction = fit.prediction;
  const auto& p = prediction.puncture;
  const std::string what = fit.predicted_only ? "predicted after calibration" : "fitted";
  const std::vector<double>& depths = prediction.curve.depth;
  const double reached = depths.empty() ? 0.0 : depths.back();  // m
  // Where the run ended and why, in its own words (never "within 2 mm" unless it got there).
  const std::string ended = fmt::format("no puncture up to {:.4g} um, where the FE run ended ({})", reached * 1e6,
                                        prediction.reason);
  if (fit.name.rfind("cylinder", 0) == 0) {
    report.input(fmt::format("cylinder, {}: {}; experiment: no puncture within 2 mm, so {}", what,
                             p ? fmt::format("punctures at {:.4g} mm, {:.4g} N", p->depth * 1e3, p->force) : ended,
                             p && p->depth < 2e-3 ? "the prediction contradicts it"
                             : reached >= 2e-3   ? "the prediction agrees"
                                                 : "the prediction agrees as far as the FE reached"));
    return;
  }
  const std::string key = fit.name.rfind("sharp", 0) == 0 ? "sharp_bevel" : "blunt_bevel";
  const std::string label = key == "sharp_bevel" ? "sharp bevel" : "blunt bevel";
  const PublishedValue& measured_depth = published.at(fmt::format("6.2.{}.puncture_depth", key));
  const PublishedValue& measured_force = published.at(fmt::format("6.2.{}.puncture_force", key));
  if (p) {
    report.compare(measured_depth, p->depth * 1e3, fmt::format("{}: puncture depth, {}", label, what),
                   "E and P_c calibrated on the sharp bevel");
    report.compare(measured_force, p->force, fmt::format("{}: puncture force, {}", label, what),
                   "E and P_c calibrated on the sharp bevel");
    return;
  }
  const double experiment_depth = measured_depth.value * 1e-3;  // m (printed in mm)
  if (reached >= experiment_depth && depths.size() >= 2) {
    // No puncture, but the model went past the experiment's puncture depth: its force there is the comparison.
    const auto upper = std::lower_bound(depths.begin(), depths.end(), experiment_depth);
    const size_t k = static_cast<size_t>(std::max<std::ptrdiff_t>(upper - depths.begin(), 1));
    const double t = (experiment_depth - depths[k - 1]) / (depths[k] - depths[k - 1]);
    const double force = prediction.curve.force[k - 1] + t * (prediction.curve.force[k] - prediction.curve.force[k - 1]);
    report.compare(measured_force, force,
                   fmt::format("{}: force at the experiment's puncture depth ({} mm), {}", label,
                               measured_depth.printed, what),
                   fmt::format("E and P_c calibrated on the sharp bevel; the model does not puncture there ({})",
                               ended));
    return;
  }
  report.input(fmt::format("{}, {}: {}; the experiment punctures deeper, at {} mm / {} N, so the prediction neither "
                           "confirms nor contradicts it",
                           label, what, ended, measured_depth.printed, measured_force.printed));
}

}  // namespace

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
  for (const calibration::FittedParameter& p : result.parameters) {
    // The interval says how far the data pin the value down; one wider than the value itself is "not determined".
    const bool determined = p.ci95 && p.ci95->first > 0 && p.ci95->second < 2 * p.value;
    fitted += fmt::format("{}{} = {}{}{}", fitted.empty() ? "" : ", ", p.spec.path,
                          calibration::as_given(p.spec, p.value), p.at_bound ? " (at its bound)" : "",
                          determined ? fmt::format(" (95 % interval {} to {})", calibration::as_given(p.spec, p.ci95->first),
                                                   calibration::as_given(p.spec, p.ci95->second))
                                     : " (not determined by the data)");
  }
  report.input(fmt::format("examples/{}: fitted on the sharp bevel's puncture point and its quadratic pre-puncture "
                           "rise: {} ({}, {} iterations, rms {:.3g})",
                           example, fitted, calibration::to_string(result.status), result.iterations,
                           result.rms_relative));
  for (const calibration::ExperimentFit& fit : result.experiments) compare_experiment(*context.published, report, fit);
  report.deviation("The calibrated rows fit E and P_c to the sharp bevel's experiment; the blunt bevel and the cylinder "
                   "are predictions with no further fitting (docs/calibration.md says what they can claim).");
  progress(0.5, "calibration done");
}

}  // namespace needlekit::cli::reproduce
