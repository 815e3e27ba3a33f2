// needlekit/calibration: calibration files, the fit (`needlekit calibrate`: GIL released, progress per iteration,
// Ctrl-C stops it at the next iteration), its JSON and curves as the CLI writes them, and case files written back
// with the fitted values. Case-file values are read and replaced in place by case_value / with_case_value.
#include <fmt/format.h>

#include "common.hpp"
#include "enum_binding.hpp"
#include "parameters.hpp"
#include "needlekit/calibration/calibrate.hpp"
#include "needlekit/calibration/calibration_output.hpp"
#include "needlekit/calibration/calibration_solver_parameters.hpp"
#include "needlekit/calibration/case_parameters.hpp"
#include "needlekit/io/result_writers.hpp"

namespace needlekit::python {
namespace {

using namespace calibration;

void bind_problem(py::module_& m) {
  bind_enum<kExperimentKindNames>(m, "ExperimentKind", "What an experiment's case file is.");
  py::class_<ParameterSpec>(m, "ParameterSpec", "A fitted parameter: a TOML path of the case files, SI values.")
      .def_readonly("path", &ParameterSpec::path, "e.g. 'tissue.layers.0.youngs_modulus'")
      .def_readonly("dimension", &ParameterSpec::dimension)
      .def_readonly("unit", &ParameterSpec::unit, "the unit the calibration file gave the initial value in")
      .def_readonly("initial", &ParameterSpec::initial, "SI")
      .def_readonly("lower", &ParameterSpec::lower, "SI")
      .def_readonly("upper", &ParameterSpec::upper, "SI");
  py::class_<MeasuredPuncture>(m, "MeasuredPuncture")
      .def_readonly("depth", &MeasuredPuncture::depth, "m, or None")
      .def_readonly("force", &MeasuredPuncture::force, "N, or None");
  py::class_<ExperimentSpec>(m, "ExperimentSpec", "An experiment: a case file and its measured data.")
      .def_readonly("name", &ExperimentSpec::name)
      .def_readonly("case_path", &ExperimentSpec::case_path)
      .def_readonly("case_text", &ExperimentSpec::case_text)
      .def_readonly("kind", &ExperimentSpec::kind)
      .def_readonly("measured_path", &ExperimentSpec::measured_path)
      .def_readonly("measured", &ExperimentSpec::measured, "ForceDepthCurve (SI), or None")
      .def_readonly("puncture", &ExperimentSpec::puncture)
      .def_readonly("curve_weight", &ExperimentSpec::curve_weight)
      .def_readonly("puncture_weight", &ExperimentSpec::puncture_weight);
  py::class_<SolverSettings> solver(m, "CalibrationSolverSettings", "The [solver] table of a calibration file.");
  def_parameters<SolverSettings>(solver, kCalibrationSolverParameters);  // every field; keyword init
  py::class_<CalibrationProblem>(m, "CalibrationProblem", "A calibration file as read (read_calibration_file).")
      .def_readonly("name", &CalibrationProblem::name)
      .def_readonly("file", &CalibrationProblem::file)
      .def_readonly("parameters", &CalibrationProblem::parameters)
      .def_readonly("experiments", &CalibrationProblem::experiments)
      .def_readwrite("solver", &CalibrationProblem::solver);
  m.def("read_calibration_file", &read_calibration_file, py::arg("path"),
        "Reads and checks a calibration file (`needlekit calibrate`); raises InvalidInput / IoError naming the file, "
        "line and key.");
}

void bind_result(py::module_& m) {
  bind_enum<kCalibrationStatusNames>(m, "CalibrationStatus", "The outcome of a calibration.");
  py::class_<CalibrationProgress>(m, "CalibrationProgress", "Passed to calibrate's progress callback per iteration.")
      .def_readonly("iteration", &CalibrationProgress::iteration, "0: the initial point")
      .def_readonly("rms_relative", &CalibrationProgress::rms_relative)
      .def_readonly("values", &CalibrationProgress::values, "SI, in the order of the parameters")
      .def_readonly("model_runs", &CalibrationProgress::model_runs, "FE runs so far")
      .def_readonly("seconds", &CalibrationProgress::seconds, "s");
  py::class_<FittedParameter>(m, "FittedParameter")
      .def_readonly("spec", &FittedParameter::spec)
      .def_readonly("value", &FittedParameter::value, "SI")
      .def_readonly("standard_error", &FittedParameter::standard_error, "SI; NaN when not identifiable")
      .def_readonly("ci95", &FittedParameter::ci95, "SI (lo, hi), or None; includes discretisation_error")
      .def_readonly("discretisation_error", &FittedParameter::discretisation_error,
                    "SI, >= 0: the estimated FE mesh error, in ci95")
      .def_readonly("at_bound", &FittedParameter::at_bound);
  py::class_<Prediction>(m, "CalibrationPrediction", "The model of one experiment at the fitted values.")
      .def_readonly("ok", &Prediction::ok)
      .def_readonly("failure", &Prediction::failure)
      .def_readonly("curve", &Prediction::curve, "ForceDepthCurve (SI); empty for design files")
      .def_readonly("puncture", &Prediction::puncture, "PuncturePoint, or None")
      .def_readonly("status", &Prediction::status)
      .def_readonly("notes", &Prediction::notes);
  py::class_<ExperimentFit>(m, "ExperimentFit")
      .def_readonly("name", &ExperimentFit::name)
      .def_readonly("kind", &ExperimentFit::kind)
      .def_readonly("rms_relative", &ExperimentFit::rms_relative)
      .def_readonly("predicted_only", &ExperimentFit::predicted_only)
      .def_readonly("prediction", &ExperimentFit::prediction)
      .def_readonly("residuals", &ExperimentFit::residuals);
  py::class_<CalibrationResult>(m, "CalibrationResult", "The fit: values (SI), 95 % intervals, correlations.")
      .def_readonly("status", &CalibrationResult::status)
      .def_readonly("reason", &CalibrationResult::reason)
      .def_readonly("iterations", &CalibrationResult::iterations)
      .def_readonly("rms_relative", &CalibrationResult::rms_relative)
      .def_readonly("parameters", &CalibrationResult::parameters)
      .def_readonly("correlation", &CalibrationResult::correlation, "NaN where not identifiable")
      .def_readonly("warnings", &CalibrationResult::warnings)
      .def_readonly("experiments", &CalibrationResult::experiments)
      .def_readonly("model_runs", &CalibrationResult::model_runs)
      .def_readonly("seconds", &CalibrationResult::seconds, "s")
      .def("values", &CalibrationResult::values, "SI, in the order of the parameters");

  m.def(
      "calibrate",
      [](const CalibrationProblem& problem, py::object progress) {
        ProgressRelay relay(std::move(progress));
        CalibrationOptions options;
        options.progress = [&relay](const CalibrationProgress& p) { return relay.keep_going(p); };
        CalibrationResult result;
        {
          py::gil_scoped_release released;
          result = calibrate(problem, options);
        }
        relay.rethrow();
        return result;
      },
      py::arg("problem"), py::arg("progress") = py::none(),
      "Fits the problem's parameters (`needlekit calibrate`; GIL released). progress(CalibrationProgress) is called "
      "after every iteration; Ctrl-C (or an exception of the callback) stops the fit there and is raised. A "
      "numerical failure is a status, not an exception.");
  m.def(
      "calibration_json",
      [](const CalibrationProblem& problem, const CalibrationResult& result) {
        return to_python(calibration_json(problem, result));
      },
      py::arg("problem"), py::arg("result"), "The result as `needlekit calibrate --json` prints it (a dict).");
  m.def("calibration_curves_csv", &calibration_curves_csv, py::arg("problem"), py::arg("result"),
        "experiment,series,depth_um,force_N rows: measured and fitted curves and puncture points.");
  m.def("calibrated_case_text", &calibrated_case_text, py::arg("problem"), py::arg("experiment"), py::arg("values"),
        "The case file of experiment `experiment` (index) with `values` (SI) written in the units the user gave "
        "(`needlekit calibrate --write-case`).");
}

void bind_case_values(py::module_& m) {
  py::class_<CaseValue>(m, "CaseValue", "A value found in a case file.")
      .def_readonly("dimension", &CaseValue::dimension)
      .def_readonly("value", &CaseValue::value, "SI")
      .def_readonly("line", &CaseValue::line, "1-based line in the case text");
  m.def("case_value", &case_value, py::arg("case_text"), py::arg("path"), py::arg("source_name") = "<text>",
        "The value at a dotted TOML path ('tissue.layers.0.youngs_modulus') of a case file's text, or None.");
  m.def(
      "with_case_value",
      [](std::string_view text, std::string_view path, py::handle value, std::string_view source_name,
         int significant_digits) {
        const std::optional<CaseValue> old = case_value(text, path, source_name);
        if (!old) {
          throw_invalid(fmt::format("{}: key '{}': not in the case, expected the path of a key that holds a number "
                                    "or a quantity",
                                    source_name, path));
        }
        std::string unit;
        if (py::isinstance<py::str>(value)) unit = unit_of(value.cast<std::string>());
        const double si = quantity(value, old->dimension, path);
        return with_case_value(text, path, si, old->dimension, unit, significant_digits);
      },
      py::arg("case_text"), py::arg("path"), py::arg("value"), py::arg("source_name") = "<text>",
      py::arg("significant_digits") = 12,
      "The case text with the value at `path` replaced (comments and layout kept): a string with a unit ('0.3 MPa') "
      "is written in that unit, an SI float in the SI unit. Raises InvalidInput when the path does not hold a value "
      "or the value has the wrong dimension. Write the text with write_text_file_atomically.");
}

}  // namespace

void bind_calibration(py::module_& m) {
  bind_problem(m);
  bind_result(m);
  bind_case_values(m);
}

}  // namespace needlekit::python
