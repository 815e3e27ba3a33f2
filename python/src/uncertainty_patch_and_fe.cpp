// needlekit/uncertainty for patches and the FE: patch_uncertainty (uncertain placement, per-needle probabilities)
// and fe_surrogate (the FE puncture under uncertain moduli through a validated response surface), their files and
// their JSON as `needlekit uncertainty` writes it. Long runs release the GIL; fe_surrogate's progress callback runs
// after every FE run and Ctrl-C stops it there.
#include "common.hpp"
#include "enum_binding.hpp"
#include "parameters.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/fe_uncertainty_config.hpp"
#include "needlekit/io/patch_uncertainty_config.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "needlekit/uncertainty/fe_surrogate.hpp"
#include "needlekit/uncertainty/fe_surrogate_parameters.hpp"
#include "needlekit/uncertainty/patch_uncertainty.hpp"

namespace needlekit::python {
namespace {

using namespace uncertainty;

// The per-needle probability of an event (a numpy array, one entry per needle in the patch's order).
py::array_t<double> needle_probabilities(const PatchUncertaintyResult& r, DesignEvent event) {
  if (event == DesignEvent::InvalidSample) throw_invalid("event: invalid_sample is a patch-level output, not per needle");
  std::vector<double> values;
  for (int n = 0; n < r.needles; ++n) values.push_back(r.needle_event(n, event).mean);
  return owning_array(std::move(values));
}

void bind_patch_uncertainty(py::module_& m) {
  py::class_<io::PatchUncertaintyFile>(m, "PatchUncertaintyFile",
                                       "A patch case plus [uncertain], [sampling] (`needlekit uncertainty`).")
      .def_readwrite("patch", &io::PatchUncertaintyFile::patch)
      .def_readwrite("inputs", &io::PatchUncertaintyFile::inputs)
      .def_readwrite("correlations", &io::PatchUncertaintyFile::correlations)
      .def_readwrite("sampling", &io::PatchUncertaintyFile::sampling);
  m.def("read_patch_uncertainty_file", &io::read_patch_uncertainty_file, py::arg("path"),
        "Reads a patch uncertainty file; raises InvalidInput naming file, line and key.");
  m.def(
      "patch_input_keys",
      [] {
        std::vector<std::tuple<std::string, std::string, std::string>> rows;
        for (const PatchInputInfo& i : patch_inputs()) rows.emplace_back(i.key, i.unit, i.meaning);
        return rows;
      },
      "The keys a patch case's [uncertain] table may name: (key, unit, meaning).");
  py::class_<PatchUncertaintyOptions> options(m, "PatchUncertaintyOptions");
  def_keyword_init<PatchUncertaintyOptions>(options);
  options.def_readwrite("sampling", &PatchUncertaintyOptions::sampling)
      .def_readwrite("success_fractions", &PatchUncertaintyOptions::success_fractions,
                     "each in (0, 1]: P(fraction of needles that succeed >= X)");
  py::class_<PatchUncertaintyResult>(m, "PatchUncertaintyResult",
                                     "Per-needle and patch-level event probabilities under uncertain placement.")
      .def_readonly("status", &PatchUncertaintyResult::status)
      .def_readonly("reason", &PatchUncertaintyResult::reason)
      .def_readonly("keys", &PatchUncertaintyResult::keys)
      .def_readonly("nominal", &PatchUncertaintyResult::nominal, "the deterministic fit and evaluation")
      .def_readonly("success_fractions", &PatchUncertaintyResult::success_fractions)
      .def_readonly("needles", &PatchUncertaintyResult::needles)
      .def_property_readonly(
          "samples", [](const PatchUncertaintyResult& r) { return r.propagation.samples; }, "N")
      .def_property_readonly(
          "outputs", [](const PatchUncertaintyResult& r) { return r.propagation.outputs; },
          "success_fraction, all_succeed, invalid_sample, one per success fraction, then per needle its events")
      .def_readonly("notes", &PatchUncertaintyResult::notes)
      .def("success_fraction", &PatchUncertaintyResult::success_fraction, py::return_value_policy::reference_internal)
      .def("all_succeed", &PatchUncertaintyResult::all_succeed, py::return_value_policy::reference_internal)
      .def("invalid_sample", &PatchUncertaintyResult::invalid_sample, py::return_value_policy::reference_internal)
      .def("at_least", &PatchUncertaintyResult::at_least, py::arg("fraction_index"),
           py::return_value_policy::reference_internal, "P(fraction >= success_fractions[fraction_index])")
      .def("needle_event", &PatchUncertaintyResult::needle_event, py::arg("needle"), py::arg("event"),
           py::return_value_policy::reference_internal)
      .def("needle_probabilities", &needle_probabilities, py::arg("event") = DesignEvent::Success,
           "The event's probability for every needle (numpy array, the patch's needle order).");
  m.def(
      "patch_uncertainty",
      [](const io::PatchUncertaintyFile& file, std::optional<PatchUncertaintyOptions> options) {
        PatchUncertaintyOptions o = options.value_or(PatchUncertaintyOptions{});
        if (!options) o.sampling = file.sampling;
        py::gil_scoped_release released;
        const geometry::BodySurface body = geometry::read_body_surface(file.patch.mesh, file.patch.mesh_unit);
        const PatchCase patch_case{&body.surface, file.patch.design, io::fit_and_evaluate_options(file.patch)};
        PatchUncertaintyResult result = patch_uncertainty(patch_case, file.inputs, file.correlations, o);
        if (body.flipped) result.notes.insert(result.notes.begin(), body.note);
        return result;
      },
      py::arg("file"), py::arg("options") = py::none(),
      "Samples placement and needle inputs of a patch case (`needlekit uncertainty` on a patch case; GIL released). "
      "options: None uses the file's [sampling].");
  m.def(
      "patch_uncertainty_json",
      [](const io::PatchUncertaintyFile& file, const PatchUncertaintyResult& result) {
        return to_python(io::patch_uncertainty_json(file, result));
      },
      py::arg("file"), py::arg("result"), "As `needlekit uncertainty --json` prints it for a patch case (a dict).");
}

void bind_fe_surrogate(py::module_& m) {
  py::class_<FeSurrogateOptions> options(m, "FeSurrogateOptions", "The FE design, held-out runs and sampling.");
  options.def_readwrite("sampling", &FeSurrogateOptions::sampling, "PropagationOptions: the [sampling] table");
  def_parameters<FeSurrogateOptions>(options, kFeSurrogateParameters);  // keyword init
  py::class_<io::FeUncertaintyFile>(m, "FeUncertaintyFile", "An indent case plus [uncertain], [sampling], [surrogate].")
      .def_readwrite("case_path", &io::FeUncertaintyFile::case_path)
      .def_readwrite("indentation", &io::FeUncertaintyFile::indentation)
      .def_readwrite("inputs", &io::FeUncertaintyFile::inputs)
      .def_readwrite("correlations", &io::FeUncertaintyFile::correlations)
      .def_readwrite("options", &io::FeUncertaintyFile::options);
  m.def("read_fe_uncertainty_file", &io::read_fe_uncertainty_file, py::arg("path"),
        "Reads an FE uncertainty file; raises InvalidInput naming file, line and key.");
  bind_enum<kFeSurrogateStatusNames>(m, "FeSurrogateStatus", "The outcome of fe_surrogate.");
  py::class_<FeRun>(m, "FeSurrogateRun", "One FE run of the surrogate's design or validation.")
      .def_readonly("inputs", &FeRun::inputs, "SI, in the order of the inputs")
      .def_readonly("status", &FeRun::status)
      .def_readonly("depth", &FeRun::depth, "m, the puncture depth (None: no puncture)")
      .def_readonly("force", &FeRun::force, "N")
      .def_readonly("surrogate_depth", &FeRun::surrogate_depth, "m")
      .def_readonly("surrogate_force", &FeRun::surrogate_force, "N")
      .def_readonly("seconds", &FeRun::seconds, "s");
  py::class_<RelativeError>(m, "RelativeError")
      .def_readonly("max", &RelativeError::max)
      .def_readonly("rms", &RelativeError::rms);
  py::class_<FeSurrogateResult>(m, "FeSurrogateResult", "The validated surrogate and the sampled FE puncture.")
      .def_readonly("status", &FeSurrogateResult::status)
      .def_readonly("reason", &FeSurrogateResult::reason)
      .def_readonly("keys", &FeSurrogateResult::keys)
      .def_readonly("nominal", &FeSurrogateResult::nominal)
      .def_readonly("elements", &FeSurrogateResult::elements)
      .def_readonly("terms", &FeSurrogateResult::terms)
      .def_readonly("design", &FeSurrogateResult::design)
      .def_readonly("validation", &FeSurrogateResult::validation)
      .def_readonly("validation_depth_error", &FeSurrogateResult::validation_depth_error, "the stated error")
      .def_readonly("validation_force_error", &FeSurrogateResult::validation_force_error, "the stated error")
      .def_readonly("design_depth_error", &FeSurrogateResult::design_depth_error)
      .def_readonly("design_force_error", &FeSurrogateResult::design_force_error)
      .def_readonly("depth_limit", &FeSurrogateResult::depth_limit, "m")
      .def_readonly("notes", &FeSurrogateResult::notes)
      .def("depth", &FeSurrogateResult::depth, py::return_value_policy::reference_internal, "m")
      .def("force", &FeSurrogateResult::force, py::return_value_policy::reference_internal, "N")
      .def("punctures_before", &FeSurrogateResult::punctures_before, py::return_value_policy::reference_internal)
      .def(
          "surrogate",
          [](const FeSurrogateResult& r, const std::vector<double>& inputs) {
            if (!r.surrogate) throw_invalid("surrogate: the fit failed, there is no surrogate (see status, reason)");
            if (inputs.size() != r.keys.size()) {
              throw_invalid("inputs: expected " + std::to_string(r.keys.size()) + " values (SI), one per key");
            }
            double depth = 0, force = 0;
            r.surrogate(inputs.data(), depth, force);
            return std::make_pair(depth, force);
          },
          py::arg("inputs"), "The fitted (puncture depth m, force N) at the inputs (SI, in the order of keys).");
  m.def(
      "fe_surrogate",
      [](const insertion::IndentationCase& c, const std::vector<DesignUncertainInput>& inputs,
         const std::vector<Correlation>& correlations, FeSurrogateOptions options, py::object progress) {
        ProgressRelay relay(std::move(progress));
        options.progress = [&relay](int done, int total) {
          if (!relay.keep_going(done, total)) throw RunStopped{};
        };
        FeSurrogateResult result;
        try {
          py::gil_scoped_release released;
          result = fe_surrogate(c, inputs, correlations, options);
        } catch (const RunStopped&) {
        }
        relay.rethrow();
        return result;
      },
      py::arg("case"), py::arg("inputs"), py::arg("correlations") = std::vector<Correlation>{},
      py::arg("options") = FeSurrogateOptions{}, py::arg("progress") = py::none(),
      "FE puncture under uncertain layer moduli / critical pressure: FE design, response surface checked on held-out "
      "runs, sampling (GIL released). progress(done, total) after every FE run; Ctrl-C stops there.");
  m.def(
      "fe_uncertainty_json",
      [](const io::FeUncertaintyFile& file, const FeSurrogateResult& result) {
        return to_python(io::fe_uncertainty_json(file, result));
      },
      py::arg("file"), py::arg("result"), "As `needlekit uncertainty --json` prints it for an FE case (a dict).");
}

}  // namespace

void bind_uncertainty_patch_and_fe(py::module_& m) {
  bind_patch_uncertainty(m);
  bind_fe_surrogate(m);
}

}  // namespace needlekit::python
