// needlekit/uncertainty: distributions, uncertainty files, design_uncertainty (`needlekit uncertainty`) and
// robust_design (`needlekit optimize` with min_success_probability), with their JSON as the CLI writes it.
#include <string>

#include "common.hpp"
#include "enum_binding.hpp"
#include "parameters.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/uncertainty_config.hpp"
#include "needlekit/io/uncertainty_output.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"
#include "needlekit/uncertainty/propagation_parameters.hpp"
#include "needlekit/uncertainty/robust_design.hpp"

namespace needlekit::python {
namespace {

using namespace uncertainty;

void bind_distributions(py::module_& m) {
  bind_enum<kDistributionKindNames>(m, "DistributionKind", "The distributions of an uncertain input.");
  py::class_<Distribution> d(m, "Distribution", "A distribution of one input, SI values (see DistributionKind).");
  def_keyword_init<Distribution>(d);
  d.def_readwrite("kind", &Distribution::kind)
      .def_readwrite("mean", &Distribution::mean, "normal, truncated-normal: mu (SI)")
      .def_readwrite("sd", &Distribution::sd, "normal, truncated-normal: sigma >= 0 (SI)")
      .def_readwrite("median", &Distribution::median, "lognormal: e^mu > 0 (SI)")
      .def_readwrite("sigma_log", &Distribution::sigma_log, "lognormal: sigma of ln x, >= 0")
      .def_readwrite("min", &Distribution::min, "truncated-normal, uniform, triangular: lower bound (SI)")
      .def_readwrite("max", &Distribution::max, "upper bound (SI)")
      .def_readwrite("mode", &Distribution::mode, "triangular: min <= mode <= max (SI)");
  m.def("distribution_cdf", &cdf, py::arg("distribution"), py::arg("x"), "F(x).");
  m.def("distribution_quantile", &quantile, py::arg("distribution"), py::arg("u"), "F^-1(u), u in (0, 1).");
  m.def("validate_distribution", &validate, py::arg("distribution"), py::arg("what") = "distribution");

  bind_enum<kSamplingMethodNames>(m, "SamplingMethod", "How the samples are drawn.");
  py::class_<PropagationOptions> sampling(m, "PropagationOptions", "The [sampling] table of an uncertainty file.");
  def_parameters<PropagationOptions>(sampling, kPropagationParameters);  // every field but progress; keyword init

  py::class_<DesignUncertainInput> input(m, "DesignUncertainInput", "An uncertain input of a design.");
  def_keyword_init<DesignUncertainInput>(input);
  input.def_readwrite("key", &DesignUncertainInput::key, "a design-file key, e.g. 'needle.tip_diameter'")
      .def_readwrite("distribution", &DesignUncertainInput::distribution)
      .def_readwrite("centred_on_nominal", &DesignUncertainInput::centred_on_nominal,
                     "the mean/median/mode is the design's value");
  py::class_<Correlation> correlation(m, "Correlation", "Correlation of the normal scores of two inputs.");
  def_keyword_init<Correlation>(correlation);
  correlation.def_readwrite("first", &Correlation::first, "index into the inputs")
      .def_readwrite("second", &Correlation::second, "index into the inputs")
      .def_readwrite("rho", &Correlation::rho, "(-1, 1)");
  m.def(
      "design_input_keys",
      [] {
        std::vector<std::tuple<std::string, std::string, std::string>> rows;
        for (const DesignInputInfo& i : design_inputs()) rows.emplace_back(i.key, i.unit, i.meaning);
        return rows;
      },
      "The keys a design's [uncertain] table may name: (key, unit, meaning).");
}

void bind_results(py::module_& m) {
  bind_enum<kDesignEventNames>(m, "DesignEvent", "The events whose probabilities design_uncertainty estimates.");
  py::class_<Interval>(m, "Interval").def_readonly("lo", &Interval::lo).def_readonly("hi", &Interval::hi);
  py::class_<SobolIndex>(m, "SobolIndex")
      .def_readonly("value", &SobolIndex::value, "NaN when undefined")
      .def_readonly("ci95", &SobolIndex::ci95);
  py::class_<OutputSummary>(m, "OutputSummary", "One output's distribution: a probability for an event.")
      .def_readonly("name", &OutputSummary::name)
      .def_readonly("defined", &OutputSummary::defined, "samples where the output is defined")
      .def_readonly("mean", &OutputSummary::mean, "the probability for an event; SI otherwise")
      .def_readonly("ci95", &OutputSummary::ci95, "of the mean")
      .def_readonly("sd", &OutputSummary::sd)
      .def_readonly("q05", &OutputSummary::q05)
      .def_readonly("q50", &OutputSummary::q50)
      .def_readonly("q95", &OutputSummary::q95)
      .def_readonly("histogram_edges", &OutputSummary::histogram_edges)
      .def_readonly("histogram_counts", &OutputSummary::histogram_counts)
      .def_readonly("first", &OutputSummary::first, "first-order Sobol' indices, per input")
      .def_readonly("total", &OutputSummary::total, "total Sobol' indices, per input");
  py::class_<OneAtATime>(m, "OneAtATime", "The index with one input at its 5 % and 95 % quantiles (Fig 6.18).")
      .def_readonly("key", &OneAtATime::key)
      .def_readonly("low", &OneAtATime::low, "SI")
      .def_readonly("high", &OneAtATime::high, "SI")
      .def_readonly("index_low", &OneAtATime::index_low, "1/m")
      .def_readonly("index_high", &OneAtATime::index_high, "1/m");
  bind_enum<kUncertaintyStatusNames>(m, "UncertaintyStatus", "The outcome of design_uncertainty.");
  py::class_<DesignUncertaintyResult>(m, "DesignUncertaintyResult",
                                      "Event probabilities, the index's distribution (1/m) and Sobol' indices.")
      .def_readonly("status", &DesignUncertaintyResult::status)
      .def_readonly("reason", &DesignUncertaintyResult::reason)
      .def_readonly("keys", &DesignUncertaintyResult::keys, "the uncertain inputs, as given")
      .def_readonly("nominal", &DesignUncertaintyResult::nominal, "the deterministic evaluation")
      .def_property_readonly(
          "samples", [](const DesignUncertaintyResult& r) { return r.propagation.samples; }, "N")
      .def_property_readonly(
          "evaluations", [](const DesignUncertaintyResult& r) { return r.propagation.evaluations; })
      .def_property_readonly(
          "outputs", [](const DesignUncertaintyResult& r) { return r.propagation.outputs; },
          "performance_index, then one per DesignEvent")
      .def_readonly("one_at_a_time", &DesignUncertaintyResult::one_at_a_time)
      .def_readonly("notes", &DesignUncertaintyResult::notes)
      .def("index", &DesignUncertaintyResult::index, py::return_value_policy::reference_internal,
           "The performance index's summary (1/m).")
      .def("event", &DesignUncertaintyResult::event, py::arg("event"), py::return_value_policy::reference_internal,
           "An event's summary: .mean is its probability, .ci95 its 95 % interval.");
}

void bind_files_and_runs(py::module_& m) {
  py::class_<DesignCase> design_case(m, "DesignCase", "One needle array with its conditions and options.");
  def_keyword_init<DesignCase>(design_case);
  design_case.def_readwrite("design", &DesignCase::design)
      .def_readwrite("conditions", &DesignCase::conditions)
      .def_readwrite("options", &DesignCase::options);
  py::class_<io::UncertaintyFile>(m, "UncertaintyFile", "An uncertainty file: a design plus [uncertain], [sampling].")
      .def_readwrite("design", &io::UncertaintyFile::design)
      .def_readwrite("inputs", &io::UncertaintyFile::inputs)
      .def_readwrite("correlations", &io::UncertaintyFile::correlations)
      .def_readwrite("sampling", &io::UncertaintyFile::sampling);
  m.def("read_uncertainty_file", &io::read_uncertainty_file, py::arg("path"),
        "Reads an uncertainty file (`needlekit uncertainty`); raises InvalidInput naming file, line and key.");
  m.def("parse_uncertainty_toml", &io::parse_uncertainty_toml, py::arg("text"), py::arg("source_name") = "<text>");

  py::class_<DesignUncertaintyOptions> options(m, "DesignUncertaintyOptions");
  def_keyword_init<DesignUncertaintyOptions>(options);
  options.def_readwrite("sampling", &DesignUncertaintyOptions::sampling);
  m.def(
      "design_uncertainty",
      [](const DesignCase& nominal, const std::vector<DesignUncertainInput>& inputs,
         const std::vector<Correlation>& correlations, const DesignUncertaintyOptions& options) {
        py::gil_scoped_release released;
        return design_uncertainty(nominal, inputs, correlations, options);
      },
      py::arg("nominal"), py::arg("inputs"), py::arg("correlations") = std::vector<Correlation>{},
      py::arg("options") = DesignUncertaintyOptions{},
      "Samples the uncertain inputs and evaluates every sample (`needlekit uncertainty`; GIL released, 10^6 "
      "analytic samples take well under a second). Raises InvalidInput naming the key.");
  m.def(
      "uncertainty_json",
      [](const io::UncertaintyFile& file, const DesignUncertaintyResult& result) {
        return to_python(io::uncertainty_json(file, result));
      },
      py::arg("file"), py::arg("result"), "The result as `needlekit uncertainty --json` prints it (a dict).");

  py::class_<io::RobustSpec>(m, "RobustSpec", "A design-space file's min_success_probability and its inputs.")
      .def_readwrite("min_success_probability", &io::RobustSpec::min_success_probability)
      .def_readwrite("inputs", &io::RobustSpec::inputs)
      .def_readwrite("correlations", &io::RobustSpec::correlations)
      .def_readwrite("sampling", &io::RobustSpec::sampling);
  py::class_<RobustDesignOptions> robust(m, "RobustDesignOptions");
  def_keyword_init<RobustDesignOptions>(robust);
  robust.def_readwrite("min_success_probability", &RobustDesignOptions::min_success_probability, "(0, 1]")
      .def_readwrite("sampling", &RobustDesignOptions::sampling, "per candidate")
      .def_readwrite("optimizer", &RobustDesignOptions::optimizer)
      .def_readwrite("max_candidates", &RobustDesignOptions::max_candidates, ">= 1");
  bind_enum<kRobustStatusNames>(m, "RobustStatus", "The outcome of robust_design.");
  py::class_<CandidateCheck>(m, "CandidateCheck")
      .def_readonly("candidate", &CandidateCheck::candidate)
      .def_readonly("success_probability", &CandidateCheck::success_probability)
      .def_readonly("ci95", &CandidateCheck::ci95);
  py::class_<RobustDesignResult>(m, "RobustDesignResult")
      .def_readonly("status", &RobustDesignResult::status)
      .def_readonly("reason", &RobustDesignResult::reason)
      .def_readonly("min_success_probability", &RobustDesignResult::min_success_probability)
      .def_readonly("nominal", &RobustDesignResult::nominal, "the deterministic ranking")
      .def_readonly("checked", &RobustDesignResult::checked, "best nominal first")
      .def_readonly("robust", &RobustDesignResult::robust, "the best nominal design that meets the level, or None")
      .def_readonly("index_cost", &RobustDesignResult::index_cost, "1/m")
      .def_readonly("index_cost_fraction", &RobustDesignResult::index_cost_fraction);
  m.def(
      "robust_design",
      [](const analysis::DesignSpace& space, const std::vector<DesignUncertainInput>& inputs,
         const std::vector<Correlation>& correlations, const RobustDesignOptions& options) {
        py::gil_scoped_release released;
        return robust_design(space, inputs, correlations, options);
      },
      py::arg("space"), py::arg("inputs"), py::arg("correlations") = std::vector<Correlation>{},
      py::arg("options") = RobustDesignOptions{},
      "The best nominal design whose P(success) meets options.min_success_probability (`needlekit optimize` with "
      "min_success_probability; GIL released).");
  m.def(
      "robust_design_json",
      [](const analysis::DesignSpace& space, const RobustDesignOptions& options, const RobustDesignResult& result) {
        return to_python(io::robust_design_json(space, options, result));
      },
      py::arg("space"), py::arg("options"), py::arg("result"), "As `needlekit optimize --json` prints it (a dict).");
}

}  // namespace

void bind_uncertainty(py::module_& m) {
  bind_distributions(m);
  bind_results(m);
  bind_files_and_runs(m);
}

}  // namespace needlekit::python
