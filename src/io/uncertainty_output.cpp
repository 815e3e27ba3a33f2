#include "needlekit/io/uncertainty_output.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/io/result_writers.hpp"

namespace needlekit::io {
namespace {

using uncertainty::DesignEvent;
using uncertainty::OutputSummary;

constexpr double kPerUm = 1e-6;  // 1/m to 1/um

nlohmann::json number(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); }
nlohmann::json interval(const uncertainty::Interval& i, double scale = 1) {
  return nlohmann::json::array({number(i.lo * scale), number(i.hi * scale)});
}

nlohmann::json sobol_of(const OutputSummary& summary, const std::vector<std::string>& keys) {
  nlohmann::json first = nlohmann::json::object(), total = nlohmann::json::object();
  nlohmann::json first_ci = nlohmann::json::object(), total_ci = nlohmann::json::object();
  for (std::size_t i = 0; i < summary.first.size(); ++i) {
    first[keys[i]] = number(summary.first[i].value);
    total[keys[i]] = number(summary.total[i].value);
    first_ci[keys[i]] = interval(summary.first[i].ci95);
    total_ci[keys[i]] = interval(summary.total[i].ci95);
  }
  return {{"first", first}, {"total", total}, {"first_ci95", first_ci}, {"total_ci95", total_ci}};
}

}  // namespace

nlohmann::json uncertainty_json(const UncertaintyFile& file, const uncertainty::DesignUncertaintyResult& r) {
  nlohmann::json json;
  const uncertainty::PropagationOptions& sampling = file.sampling;
  json["samples"] = r.propagation.samples;
  json["method"] = uncertainty::to_string(sampling.method);
  json["seed"] = sampling.seed;
  json["evaluations"] = r.propagation.evaluations;
  json["status"] = uncertainty::to_string(r.status);
  json["reason"] = r.reason;

  nlohmann::json inputs = nlohmann::json::array();
  std::vector<std::string> notes_unused;
  const uncertainty::InputTransform transform =
      uncertainty::design_input_transform(file.design, file.inputs, file.correlations, notes_unused);
  for (const uncertainty::UncertainInput& input : transform.inputs()) {
    const auto& entry = uncertainty::info(uncertainty::design_input_from_key(input.key, input.key));
    const double factor = units::unit_factor(entry.unit, entry.dimension, input.key);
    inputs.push_back({{"key", input.key}, {"distribution", uncertainty::describe(input.distribution, factor, entry.unit)}});
  }
  json["inputs"] = inputs;

  nlohmann::json probabilities = nlohmann::json::object();
  for (const auto& event : uncertainty::design_events()) {
    const OutputSummary& s = r.event(event.event);
    probabilities[std::string(event.name)] = {
        {"value", number(s.mean)}, {"ci95", interval(s.ci95)}, {"samples_defined", s.defined}};
  }
  json["probabilities"] = probabilities;

  const OutputSummary& index = r.index();
  nlohmann::json edges = nlohmann::json::array();
  for (double edge : index.histogram_edges) edges.push_back(edge * kPerUm);
  json["performance_index_per_um"] = {
      {"mean", number(index.mean * kPerUm)}, {"ci95_mean", interval(index.ci95, kPerUm)},
      {"sd", number(index.sd * kPerUm)},     {"q05", number(index.q05 * kPerUm)},
      {"q50", number(index.q50 * kPerUm)},   {"q95", number(index.q95 * kPerUm)},
      {"histogram", {{"edges", edges}, {"counts", index.histogram_counts}}}};
  json["nominal"] = {{"performance_index_per_um", r.nominal.performance_index * kPerUm},
                     {"status", analysis::to_string(r.nominal.status)}};

  if (!index.first.empty()) {
    nlohmann::json sobol = sobol_of(index, r.keys);
    nlohmann::json events = nlohmann::json::object();
    for (const auto& event : uncertainty::design_events()) {
      events[std::string(event.name)] = sobol_of(r.event(event.event), r.keys);
    }
    sobol["events"] = events;
    json["sobol"] = sobol;
  } else {
    json["sobol"] = nullptr;
  }

  nlohmann::json oat = nlohmann::json::object();
  for (const uncertainty::OneAtATime& o : r.one_at_a_time) {
    const auto& entry = uncertainty::info(uncertainty::design_input_from_key(o.key, o.key));
    const double factor = units::unit_factor(entry.unit, entry.dimension, o.key);
    oat[o.key] = {{"low", o.low / factor},
                  {"high", o.high / factor},
                  {"unit", entry.unit},
                  {"performance_index_low_per_um", o.index_low * kPerUm},
                  {"performance_index_high_per_um", o.index_high * kPerUm}};
  }
  json["one_at_a_time"] = oat;
  json["notes"] = r.notes;
  return json;
}

nlohmann::json robust_design_json(const analysis::DesignSpace& space, const uncertainty::RobustDesignOptions& options,
                                  const uncertainty::RobustDesignResult& r) {
  nlohmann::json json = optimizer_json(space, r.nominal);
  const auto check_json = [](const uncertainty::CandidateCheck& c) {
    nlohmann::json entry = candidate_json(c.candidate);
    entry["success_probability"] = c.success_probability;
    entry["success_ci95"] = interval(c.ci95);
    return entry;
  };
  nlohmann::json robust = {
      {"min_success_probability", r.min_success_probability},
      {"status", uncertainty::to_string(r.status)},
      {"reason", r.reason},
      {"samples", options.sampling.samples},
      {"method", uncertainty::to_string(options.sampling.method)},
      {"seed", options.sampling.seed},
      {"candidates_checked", r.checked.size()},
      {"design", r.robust ? check_json(*r.robust) : nlohmann::json(nullptr)},
      {"nominal_optimum", r.checked.empty() ? nlohmann::json(nullptr) : check_json(r.checked.front())},
      {"index_cost_per_um", r.robust ? nlohmann::json(r.index_cost * kPerUm) : nlohmann::json(nullptr)},
      {"index_cost_percent", r.robust ? nlohmann::json(100 * r.index_cost_fraction) : nlohmann::json(nullptr)},
  };
  json["robust"] = robust;
  return json;
}

std::string index_histogram_csv(const uncertainty::DesignUncertaintyResult& r) {
  std::string csv = "performance_index_low_per_um,performance_index_high_per_um,count\n";
  const OutputSummary& index = r.index();
  for (std::size_t b = 0; b < index.histogram_counts.size(); ++b) {
    csv += fmt::format("{:.9g},{:.9g},{}\n", index.histogram_edges[b] * kPerUm, index.histogram_edges[b + 1] * kPerUm,
                       index.histogram_counts[b]);
  }
  return csv;
}

std::string sobol_csv(const uncertainty::DesignUncertaintyResult& r) {
  std::string csv = "output,input,first,first_lo,first_hi,total,total_lo,total_hi\n";
  const auto field = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string(); };
  for (const OutputSummary& s : r.propagation.outputs) {
    for (std::size_t i = 0; i < s.first.size(); ++i) {
      csv += fmt::format("{},{},{},{},{},{},{},{}\n", s.name, r.keys[i], field(s.first[i].value),
                         field(s.first[i].ci95.lo), field(s.first[i].ci95.hi), field(s.total[i].value),
                         field(s.total[i].ci95.lo), field(s.total[i].ci95.hi));
    }
  }
  return csv;
}

}  // namespace needlekit::io
