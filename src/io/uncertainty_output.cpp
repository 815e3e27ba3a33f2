#include "needlekit/io/uncertainty_output.hpp"

#include <cmath>
#include <functional>
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

nlohmann::json probability_of(const OutputSummary& s) {
  return {{"value", number(s.mean)}, {"ci95", interval(s.ci95)}, {"samples_defined", s.defined}};
}

// mean, ci95_mean, sd, quantiles and histogram of a continuous output, scaled.
nlohmann::json distribution_of(const OutputSummary& s, double scale) {
  nlohmann::json edges = nlohmann::json::array();
  for (double edge : s.histogram_edges) edges.push_back(edge * scale);
  return {{"mean", number(s.mean * scale)}, {"ci95_mean", interval(s.ci95, scale)},
          {"sd", number(s.sd * scale)},     {"q05", number(s.q05 * scale)},
          {"q50", number(s.q50 * scale)},   {"q95", number(s.q95 * scale)},
          {"histogram", {{"edges", edges}, {"counts", s.histogram_counts}}}};
}

// "samples" .. "reason" and "inputs".
nlohmann::json study_header(const uncertainty::PropagationOptions& sampling, const uncertainty::PropagationResult& p,
                            uncertainty::UncertaintyStatus status, const std::string& reason,
                            const uncertainty::InputTransform& transform,
                            const std::function<std::pair<std::string_view, units::Dimension>(const std::string&)>& unit_of) {
  nlohmann::json json;
  json["samples"] = p.samples;
  json["method"] = uncertainty::to_string(sampling.method);
  json["seed"] = sampling.seed;
  json["evaluations"] = p.evaluations;
  json["status"] = uncertainty::to_string(status);
  json["reason"] = reason;
  nlohmann::json inputs = nlohmann::json::array();
  for (const uncertainty::UncertainInput& input : transform.inputs()) {
    const auto [unit, dimension] = unit_of(input.key);
    const double factor = units::unit_factor(unit, dimension, input.key);
    inputs.push_back({{"key", input.key}, {"distribution", uncertainty::describe(input.distribution, factor, unit)}});
  }
  json["inputs"] = inputs;
  return json;
}

constexpr uncertainty::DesignEvent kNeedleEventList[] = {
    DesignEvent::Puncture, DesignEvent::BucklingFailure, DesignEvent::BendingFailure, DesignEvent::ReachesTarget,
    DesignEvent::Success};

}  // namespace

nlohmann::json uncertainty_json(const UncertaintyFile& file, const uncertainty::DesignUncertaintyResult& r) {
  std::vector<std::string> notes_unused;
  const uncertainty::InputTransform transform =
      uncertainty::design_input_transform(file.design, file.inputs, file.correlations, notes_unused);
  nlohmann::json json = study_header(file.sampling, r.propagation, r.status, r.reason, transform, [](const std::string& key) {
    const auto& entry = uncertainty::info(uncertainty::design_input_from_key(key, key));
    return std::pair{entry.unit, entry.dimension};
  });

  nlohmann::json probabilities = nlohmann::json::object();
  for (const auto& event : uncertainty::kDesignEventNames) {
    probabilities[std::string(event.name)] = probability_of(r.event(event.value));
  }
  json["probabilities"] = probabilities;

  const OutputSummary& index = r.index();
  json["performance_index_per_um"] = distribution_of(index, kPerUm);
  json["nominal"] = {{"performance_index_per_um", r.nominal.performance_index * kPerUm},
                     {"status", analysis::to_string(r.nominal.status)}};

  if (!index.first.empty()) {
    nlohmann::json sobol = sobol_of(index, r.keys);
    nlohmann::json events = nlohmann::json::object();
    for (const auto& event : uncertainty::kDesignEventNames) {
      events[std::string(event.name)] = sobol_of(r.event(event.value), r.keys);
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

nlohmann::json patch_uncertainty_json(const PatchUncertaintyFile& file, const uncertainty::PatchUncertaintyResult& r) {
  std::vector<std::string> notes_unused;
  const uncertainty::InputTransform transform = uncertainty::patch_input_transform(
      file.patch.design, fit_and_evaluate_options(file.patch), file.inputs, file.correlations, notes_unused);
  nlohmann::json json = study_header(file.sampling, r.propagation, r.status, r.reason, transform, [](const std::string& key) {
    const auto& entry = uncertainty::patch_input_from_key(key, key);
    return std::pair{entry.unit, entry.dimension};
  });
  nlohmann::json probabilities = nlohmann::json::object();
  probabilities[std::string(uncertainty::kAllSucceedOutput)] = probability_of(r.all_succeed());
  for (std::size_t f = 0; f < r.success_fractions.size(); ++f) {
    probabilities[r.at_least(f).name] = probability_of(r.at_least(f));
  }
  probabilities[r.invalid_sample().name] = probability_of(r.invalid_sample());
  json["probabilities"] = probabilities;
  json["success_fraction"] = distribution_of(r.success_fraction(), 1);
  int nominal_successes = 0;
  for (const patch::NeedleState& s : r.nominal.evaluation.needles) nominal_successes += s.status == "ok";
  json["nominal"] = {{"fit_status", patch::to_string(r.nominal.status)},
                     {"success_fraction", static_cast<double>(nominal_successes) / r.needles},
                     {"needles", r.needles}};
  if (!r.success_fraction().first.empty()) {
    nlohmann::json sobol = sobol_of(r.success_fraction(), r.keys);
    nlohmann::json events = nlohmann::json::object();
    events[std::string(uncertainty::kAllSucceedOutput)] = sobol_of(r.all_succeed(), r.keys);
    for (std::size_t f = 0; f < r.success_fractions.size(); ++f) events[r.at_least(f).name] = sobol_of(r.at_least(f), r.keys);
    sobol["events"] = events;
    json["sobol"] = sobol;
  } else {
    json["sobol"] = nullptr;
  }
  nlohmann::json needles = nlohmann::json::array();
  const patch::PatchDesign& design = r.nominal.design;
  for (int k = 0; k < r.needles; ++k) {
    const Eigen::Vector3d& p = r.nominal.fit.positions[k];
    nlohmann::json events = nlohmann::json::object();
    for (DesignEvent event : kNeedleEventList) {
      const OutputSummary& s = r.needle_event(k, event);
      events[std::string(uncertainty::to_string(event))] = {{"value", number(s.mean)}, {"ci95", interval(s.ci95)}};
    }
    needles.push_back({{"index", k},
                       {"i", design.column(k)},
                       {"j", design.row(k)},
                       {"position_mm", {p.x() * 1e3, p.y() * 1e3, p.z() * 1e3}},
                       {"probabilities", events}});
  }
  json["needles"] = needles;
  json["notes"] = r.notes;
  return json;
}

std::string patch_probability_csv(const uncertainty::PatchUncertaintyResult& r) {
  std::string csv = "needle,i,j,x_mm,y_mm,z_mm,u_mm,v_mm";
  for (DesignEvent event : kNeedleEventList) {
    const std::string_view name = uncertainty::to_string(event);
    csv += fmt::format(",P_{0},P_{0}_lo,P_{0}_hi", name);
  }
  csv += "\n";
  const auto field = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string(); };
  const patch::PatchDesign& design = r.nominal.design;
  for (int k = 0; k < r.needles; ++k) {
    const Eigen::Vector3d& p = r.nominal.fit.positions[k];
    const Eigen::Vector2d& rest = design.rest_positions[k];
    csv += fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}", k, design.column(k), design.row(k), p.x() * 1e3,
                       p.y() * 1e3, p.z() * 1e3, rest.x() * 1e3, rest.y() * 1e3);
    for (DesignEvent event : kNeedleEventList) {
      const OutputSummary& s = r.needle_event(k, event);
      csv += fmt::format(",{},{},{}", field(s.mean), field(s.ci95.lo), field(s.ci95.hi));
    }
    csv += "\n";
  }
  return csv;
}

VtuGrid patch_probability_grid(const uncertainty::PatchUncertaintyResult& r) {
  VtuGrid grid;
  for (int k = 0; k < r.needles; ++k) {
    grid.points.push_back(r.nominal.fit.positions[k]);
    grid.cells.push_back({k});
    grid.cell_types.push_back(VtkCellType::Vertex);
  }
  for (DesignEvent event : kNeedleEventList) {
    VtuField field{fmt::format("P_{}", uncertainty::to_string(event)), 1, {}};
    for (int k = 0; k < r.needles; ++k) field.values.push_back(r.needle_event(k, event).mean);  // NaN: never defined
    grid.point_fields.push_back(std::move(field));
  }
  VtuField lo{"P_success_lo", 1, {}}, hi{"P_success_hi", 1, {}};
  for (int k = 0; k < r.needles; ++k) {
    lo.values.push_back(r.needle_event(k, DesignEvent::Success).ci95.lo);
    hi.values.push_back(r.needle_event(k, DesignEvent::Success).ci95.hi);
  }
  grid.point_fields.push_back(std::move(lo));
  grid.point_fields.push_back(std::move(hi));
  return grid;
}

nlohmann::json fe_uncertainty_json(const FeUncertaintyFile& file, const uncertainty::FeSurrogateResult& r) {
  std::vector<std::string> notes_unused;
  const uncertainty::InputTransform transform =
      uncertainty::fe_input_transform(file.indentation, file.inputs, file.correlations, notes_unused);
  nlohmann::json json = study_header(file.options.sampling, r.propagation, uncertainty::UncertaintyStatus::Ok, r.reason,
                                     transform, [](const std::string&) {
                                       return std::pair{std::string_view("MPa"), units::Dimension::Pressure};
                                     });
  json["status"] = uncertainty::to_string(r.status);  // the surrogate's status, not a design study's
  const auto error = [](const uncertainty::RelativeError& e) {
    return nlohmann::json{{"max_relative", e.max}, {"rms_relative", e.rms}};
  };
  double seconds = r.nominal.seconds;
  for (const auto* runs : {&r.design, &r.validation}) {
    for (const uncertainty::FeRun& run : *runs) seconds += run.seconds;
  }
  json["surrogate"] = {
      {"kind", r.design.empty() ? "the nominal FE run (no input varies)" : "quadratic in the log inputs"},
      {"terms", r.terms},
      {"fe_runs", 1 + r.design.size() + r.validation.size()},
      {"elements", r.elements},
      {"design_runs", r.design.size()},
      {"validation_runs", r.validation.size()},
      {"fe_seconds", seconds},
      {"validation_error", {{"puncture_depth", error(r.validation_depth_error)}, {"puncture_force", error(r.validation_force_error)}}},
      {"fit_error", {{"puncture_depth", error(r.design_depth_error)}, {"puncture_force", error(r.design_force_error)}}}};
  json["depth_limit_um"] = r.depth_limit * 1e6;
  const bool sampled = !r.propagation.outputs.empty();
  json["probabilities"] = nlohmann::json::object();
  if (sampled) json["probabilities"]["punctures_before_depth"] = probability_of(r.punctures_before());
  json["puncture_depth_um"] = sampled ? distribution_of(r.depth(), 1e6) : nlohmann::json(nullptr);
  json["puncture_force_N"] = sampled ? distribution_of(r.force(), 1) : nlohmann::json(nullptr);
  json["nominal"] = {{"puncture_depth_um", r.nominal.depth ? nlohmann::json(*r.nominal.depth * 1e6) : nlohmann::json(nullptr)},
                     {"puncture_force_N", r.nominal.force ? nlohmann::json(*r.nominal.force) : nlohmann::json(nullptr)},
                     {"status", insertion::to_string(r.nominal.status)}};
  json["sobol"] = sampled && !r.depth().first.empty() ? sobol_of(r.depth(), r.keys) : nlohmann::json(nullptr);
  json["notes"] = r.notes;
  return json;
}

std::string fe_runs_csv(const FeUncertaintyFile& file, const uncertainty::FeSurrogateResult& r) {
  std::string csv = "role";
  for (const auto& input : file.inputs) csv += fmt::format(",{}_MPa", input.key);
  csv += ",status,puncture_depth_um,puncture_force_N,surrogate_depth_um,surrogate_force_N,seconds\n";
  const auto row = [&](std::string_view role, const uncertainty::FeRun& run, bool fitted) {
    csv += role;
    for (double x : run.inputs) csv += fmt::format(",{:.6g}", x * 1e-6);
    csv += fmt::format(",{},{},{},{},{},{:.3g}\n", insertion::to_string(run.status),
                       run.depth ? fmt::format("{:.6g}", *run.depth * 1e6) : "",
                       run.force ? fmt::format("{:.6g}", *run.force) : "",
                       fitted ? fmt::format("{:.6g}", run.surrogate_depth * 1e6) : "",
                       fitted ? fmt::format("{:.6g}", run.surrogate_force) : "", run.seconds);
  };
  row("nominal", r.nominal, false);
  for (const auto& run : r.design) row("design", run, true);
  for (const auto& run : r.validation) row("validation", run, true);
  return csv;
}

}  // namespace needlekit::io
