// The calibration file reader (calibration_problem.hpp). It uses the io folder's TOML helpers (FILE:LINE messages)
// and the case readers; the calibration folder sits above io.
#include <fmt/format.h>

#include "needlekit/calibration/calibration_problem.hpp"
#include "needlekit/calibration/calibration_solver_parameters.hpp"
#include "needlekit/calibration/case_parameters.hpp"
#include "needlekit/io/toml_config.hpp"
#include "needlekit/io/toml_parameters.hpp"
#include "needlekit/io/force_curve_csv.hpp"

namespace needlekit::calibration {
namespace {

using namespace io::config;  // Section, text_of, quantity_of, ...

ExperimentKind kind_of_case(const toml::table& root) {
  if (root.get("post_puncture")) return ExperimentKind::Insertion;
  if (root.get("loading")) return ExperimentKind::Indentation;
  return ExperimentKind::Design;
}

ParameterSpec read_parameter(const Section& entry, const std::string& where) {
  ParameterSpec p;
  p.where = where;
  const toml::node& path_node = entry.required("path", "a key of the cases, e.g. \"puncture.critical_pressure\"");
  p.path = text_of(entry, path_node, "path", "a dotted key");
  if (!parameter_kind_of(p.path)) {
    entry.fail(path_node, "path",
               fmt::format("'{}' is not a calibratable key, expected one of: {}", p.path, parameter_kind_list()));
  }
  const toml::node& initial = entry.required("initial", "the initial value with its unit, e.g. \"0.1 MPa\"");
  if (initial.is_number()) {
    p.dimension = units::Dimension::Dimensionless;
    p.initial = *initial.value<double>();
  } else {
    const std::string text = text_of(entry, initial, "initial", "a value with its unit, e.g. \"0.1 MPa\"");
    p.unit = unit_of(text);
    bool found = false;
    for (units::Dimension d : {units::Dimension::Pressure, units::Dimension::Force, units::Dimension::Length,
                               units::Dimension::InverseLength, units::Dimension::Stiffness, units::Dimension::Area}) {
      try {
        p.initial = units::parse_quantity(text, d, "initial");
        p.dimension = d;
        found = true;
        break;
      } catch (const InvalidInput&) {
      }
    }
    if (!found) entry.fail(initial, "initial", fmt::format("'{}' is not a quantity with a known unit", text));
  }
  const toml::node& bounds = entry.required("bounds", "[lower, upper] with units");
  if (!bounds.is_array() || bounds.as_array()->size() != 2) {
    entry.fail(bounds, "bounds", fmt::format("{} is not [lower, upper], expected two values", describe(bounds)));
  }
  double values[2];
  for (std::size_t i = 0; i < 2; ++i) {
    const toml::node& b = *bounds.as_array()->get(i);
    const std::string key = i == 0 ? "bounds (lower)" : "bounds (upper)";
    if (p.dimension == units::Dimension::Dimensionless) {
      if (!b.is_number()) entry.fail(b, key, fmt::format("{} is not a number, expected a number like initial", describe(b)));
      values[i] = *b.value<double>();
    } else {
      values[i] = quantity_of(entry, b, key, p.dimension);
    }
  }
  p.lower = values[0];
  p.upper = values[1];
  if (!(p.lower < p.upper)) entry.fail(bounds, "bounds", "lower >= upper, expected lower < upper");
  if (!(p.initial >= p.lower && p.initial <= p.upper)) {
    entry.fail(initial, "initial", "lies outside bounds, expected lower <= initial <= upper");
  }
  if (p.initial == 0) entry.fail(initial, "initial", "is 0, expected a non-zero initial value (it sets the scale)");
  return p;
}

ExperimentSpec read_experiment(const Section& entry, const std::string& where, const std::filesystem::path& base,
                               std::size_t index) {
  ExperimentSpec e;
  e.where = where;
  e.name = fmt::format("experiment_{}", index + 1);
  if (const toml::node* node = entry.optional("name")) e.name = text_of(entry, *node, "name", "a name");
  const toml::node& case_node = entry.required("case", "an indent or insert case file, or a design file");
  const std::filesystem::path case_file = text_of(entry, case_node, "case", "a file name");
  e.case_path = case_file.is_absolute() ? case_file : base / case_file;
  e.case_text = entry.at(case_node, [&] { return read_text(e.case_path); });
  e.kind = kind_of_case(parse_toml(e.case_text, e.case_path.string()));
  if (const toml::node* node = entry.optional("measured")) {
    if (e.kind == ExperimentKind::Design) {
      entry.fail(*node, "measured", "a force-depth curve does not apply to a design file, expected puncture = {...}");
    }
    const std::filesystem::path file = text_of(entry, *node, "measured", "a CSV file with depth_<unit>, force_<unit>");
    e.measured_path = file.is_absolute() ? file : base / file;
    e.measured = entry.at(*node, [&] { return io::read_force_curve_csv(*e.measured_path); });
    if (e.measured->depth.size() < 3) {
      entry.fail(*node, "measured", fmt::format("{}: {} samples, expected at least 3", e.measured_path->string(),
                                                e.measured->depth.size()));
    }
  }
  if (const auto puncture = entry.optional_subsection("puncture", {"depth", "force"})) {
    e.puncture.depth = optional_positive_quantity(*puncture, "depth", Dimension::Length);
    e.puncture.force = optional_positive_quantity(*puncture, "force", Dimension::Force);
    if (!e.puncture.depth && !e.puncture.force) {
      entry.fail(*entry.optional("puncture"), "puncture", "is empty, expected depth and/or force");
    }
  }
  if (const auto weights = entry.optional_subsection("weights", {"curve", "puncture"})) {
    if (const toml::node* node = weights->optional("curve")) e.curve_weight = number_at_least(*weights, *node, "curve", 0);
    if (const toml::node* node = weights->optional("puncture"))
      e.puncture_weight = number_at_least(*weights, *node, "puncture", 0);
  }
  const bool prediction = e.curve_weight == 0 && e.puncture_weight == 0;
  if (!e.measured && !e.puncture.depth && !e.puncture.force && !prediction) {
    entry.fail(entry.table(), "measured",
               "missing, expected measured = \"curve.csv\" and/or puncture = { ... } (or weights = { curve = 0, "
               "puncture = 0 } for a prediction)");
  }
  return e;
}

}  // namespace

std::string_view to_string(ExperimentKind kind) { return name_of(kExperimentKindNames, kind); }

CalibrationProblem parse_calibration_toml(std::string_view text, std::string_view source_name,
                                          const std::filesystem::path& base) {
  const std::string file(source_name);
  const std::filesystem::path path(file);
  const toml::table root = parse_toml(text, file);
  const Section top(root, "", file, {"name", "solver", "parameters", "experiments"});
  CalibrationProblem problem;
  problem.file = path;
  problem.name = path.stem().string();
  if (const toml::node* node = top.optional("name")) problem.name = text_of(top, *node, "name", "a name");
  if (const auto solver =
          top.optional_subsection("solver", keys_of_group(kCalibrationSolverParameters, "solver"))) {
    read_parameters(*solver, kCalibrationSolverParameters, "solver", problem.solver);
  }
  for (std::string_view key : {"parameters", "experiments"}) {
    const toml::node& node = top.required(key, fmt::format("[[{}]] entries", key));
    if (!node.is_array_of_tables() || node.as_array()->empty()) {
      top.fail(node, key, fmt::format("{} is not an array of tables, expected [[{}]] entries", describe(node), key));
    }
  }
  const toml::array& experiments = *root.get("experiments")->as_array();
  for (std::size_t i = 0; i < experiments.size(); ++i) {
    const Section entry = top.subsection(*experiments.get(i), fmt::format("experiments[{}]", i),
                                         {"name", "case", "measured", "puncture", "weights"});
    problem.experiments.push_back(
        read_experiment(entry, fmt::format("{} experiments[{}]", location(file, experiments.get(i)->source()), i), base, i));
  }
  const toml::array& parameters = *root.get("parameters")->as_array();
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const Section entry = top.subsection(*parameters.get(i), fmt::format("parameters[{}]", i), {"path", "initial", "bounds"});
    ParameterSpec p =
        read_parameter(entry, fmt::format("{} parameters[{}]", location(file, parameters.get(i)->source()), i));
    for (const ParameterSpec& other : problem.parameters) {
      if (other.path == p.path) entry.fail(*entry.optional("path"), "path", fmt::format("'{}' is fitted twice", p.path));
    }
    // The key must exist, with the initial value's dimension, in at least one case.
    bool found = false;
    for (const ExperimentSpec& e : problem.experiments) {
      const std::optional<CaseValue> value = case_value(e.case_text, p.path, e.case_path.string());
      if (!value) continue;
      if (value->dimension != p.dimension) {
        entry.fail(*entry.optional("initial"), "initial",
                   fmt::format("is a {}, but {}:{}: '{}' is a {}, expected the same dimension",
                               units::dimension_name(p.dimension), e.case_path.string(), value->line, p.path,
                               units::dimension_name(value->dimension)));
      }
      found = true;
    }
    if (!found) {
      std::string cases;
      for (const ExperimentSpec& e : problem.experiments) cases += (cases.empty() ? "" : ", ") + e.case_path.string();
      entry.fail(*entry.optional("path"), "path",
                 fmt::format("'{}' does not exist in the case{} {} (a preset or a missing key cannot be fitted: write "
                             "the key out in the case)",
                             p.path, problem.experiments.size() > 1 ? "s" : "", cases));
    }
    problem.parameters.push_back(std::move(p));
  }
  return problem;
}

CalibrationProblem read_calibration_file(const std::filesystem::path& path) {
  return parse_calibration_toml(read_text(path), path.string(), path.has_parent_path() ? path.parent_path() : ".");
}

}  // namespace needlekit::calibration
