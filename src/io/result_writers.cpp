#include "needlekit/io/result_writers.hpp"

#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/atomic_file.hpp"
#include "needlekit/core/units.hpp"

namespace needlekit::io {
namespace {

// SI to the dissertation's units, to 12 significant digits (a value the user gave comes back as given).
double um(double metres) { return units::round_to_12_digits(metres * 1e6); }
double um2(double square_metres) { return units::round_to_12_digits(square_metres * 1e12); }
double um3(double cubic_metres) { return units::round_to_12_digits(cubic_metres * 1e18); }
double per_um(double per_metre) { return units::round_to_12_digits(per_metre * 1e-6); }
double gpa(double pascals) { return units::round_to_12_digits(pascals * 1e-9); }
double mpa(double pascals) { return units::round_to_12_digits(pascals * 1e-6); }

template <class Value, class Convert>
nlohmann::json optional_json(const std::optional<Value>& value, Convert&& convert) {
  return value ? nlohmann::json(convert(*value)) : nlohmann::json(nullptr);
}

// CSV field quoting (RFC 4180): quoted when it holds a comma, a quote or a line break.
std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

double report_value(analysis::SweepParameter parameter, double value) {
  const std::string_view unit = sweep_report_unit(parameter);
  if (unit.empty()) return value;
  return value / units::unit_factor(unit, analysis::sweep_parameter_dimension(parameter), "sweep unit");
}

}  // namespace

nlohmann::json candidate_json(const analysis::DesignCandidate& candidate) {
  return {
      {"needles_per_row", candidate.needles_per_row},
      {"tip_diameter_um", um(candidate.tip_diameter)},
      {"base_diameter_um", um(candidate.base_diameter)},
      {"bore_diameter_um", um(candidate.bore_diameter)},
      {"width_um", um(candidate.width)},
      {"length_um", um(candidate.length)},
      {"performance_index_per_um", per_um(candidate.performance_index)},
  };
}

nlohmann::json performance_json(const analysis::ArrayDesign& design, const analysis::PerformanceIndexResult& r) {
  const needle::NeedleGeometry& n = design.needle;
  const bool tapered = r.buckling.method == analysis::BucklingMethod::TaperedEigenvalue;
  return {
      // inputs
      {"shape", needle::to_string(n.shape)},
      {"hollow", n.hollow()},
      {"tip_diameter_um", um(n.tip_diameter)},
      {"base_diameter_um", um(n.base_diameter)},
      {"bore_diameter_um", um(n.bore_diameter)},
      {"length_um", um(n.length)},
      {"material", design.material.name},
      {"youngs_modulus_GPa", gpa(design.material.youngs_modulus)},
      {"yield_strength_MPa", optional_json(design.material.yield_strength, mpa)},
      {"allowable_stress_MPa", optional_json(design.material.allowable_stress, mpa)},
      {"needles_per_row", design.needles_per_row},
      {"width_um", um(design.width)},
      // puncture (§4.2) and permeation (§4.4–4.7)
      {"tip_area_um2", um2(r.tip_area)},
      {"puncture_force_N", r.puncture_force},
      {"puncture_force_law", analysis::to_string(r.puncture_force_law)},
      {"puncture_force_law_source", analysis::puncture_force_law_source(r.puncture_force_law)},
      {"puncture_force_in_range", r.puncture_force_in_range},
      {"deformation_um", um(r.deformation)},
      {"small_tip_branch", r.small_tip_branch},
      {"cutting_depth_um", um(r.cutting_depth)},
      {"permeation_depth_um", um(r.permeation_depth)},
      {"diameter_at_surface_um", um(r.diameter_at_surface)},
      {"embedded_volume_um3", um3(r.embedded_volume)},
      {"Q_um2", um2(r.q_factor)},
      {"hole_volume_um3", um3(r.hole_volume)},
      {"gap_volume_um3", um3(r.gap_volume)},
      {"pitch_um", um(r.pitch)},
      {"fractional_skin_volume", r.fractional_skin_volume},
      {"needle_volume_um3", um3(r.needle_volume)},
      // buckling and bending (§2.5, §4.3, §5.2)
      {"critical_buckling_load_N", r.buckling.critical_load},
      {"buckling_method", analysis::to_string(r.buckling.method)},
      {"buckling_end_condition", analysis::to_string(r.buckling.end_condition)},
      {"effective_length_factor", r.buckling.effective_length_factor},
      {"tapered_factor_m", tapered ? nlohmann::json(r.buckling.tapered_factor) : nlohmann::json(nullptr)},
      {"slenderness_ratio", r.buckling.slenderness_ratio},
      {"column_constant", r.buckling.column_constant > 0 ? nlohmann::json(r.buckling.column_constant)
                                                         : nlohmann::json(nullptr)},
      {"buckling_force_N", r.buckling_force},
      {"buckling_ok", r.buckling_ok},
      {"critical_bending_load_N", optional_json(r.critical_bending_load, [](double load) { return load; })},
      {"bending_force_N", r.bending_force},
      {"bending_ok", optional_json(r.bending_ok, [](bool ok) { return ok; })},
      // the index (Eqs 4.25, 5.9)
      {"performance_index_per_um", per_um(r.performance_index)},
      {"status", analysis::to_string(r.status)},
      {"reason", r.reason},
      {"notes", r.notes},
  };
}

nlohmann::json optimizer_json(const analysis::DesignSpace& space, const analysis::OptimizerResult& result) {
  nlohmann::json top = nlohmann::json::array();
  for (const analysis::DesignCandidate& candidate : result.top) {
    analysis::ArrayDesign design;
    design.needle = {space.shape, candidate.tip_diameter, candidate.base_diameter, candidate.bore_diameter,
                     candidate.length};
    design.material = space.material;
    design.needles_per_row = candidate.needles_per_row;
    design.width = candidate.width;
    nlohmann::json entry = candidate_json(candidate);
    entry["details"] = performance_json(design, candidate.details);
    top.push_back(std::move(entry));
  }
  return {
      {"shape", needle::to_string(space.shape)},
      {"hollow", space.hollow},
      {"material", space.material.name},
      {"best", result.top.empty() ? nlohmann::json(nullptr) : candidate_json(result.top.front())},
      {"evaluated", result.evaluated},
      {"feasible", result.feasible},
      {"grid_points", result.grid_points},
      {"seconds", result.seconds},
      {"status", analysis::to_string(result.status)},
      {"reason", result.reason},
      {"puncture_force_law", analysis::to_string(space.conditions.tissue.force_law.kind)},
      {"top_outside_puncture_force_law_range", result.top_outside_force_law_range},
      {"top", std::move(top)},
  };
}

std::string_view sweep_report_unit(analysis::SweepParameter parameter) {
  switch (analysis::sweep_parameter_dimension(parameter)) {
    case units::Dimension::Length: return "um";
    case units::Dimension::Angle: return "deg";
    default: return "";
  }
}

std::string sweep_value_column(analysis::SweepParameter parameter) {
  const std::string_view unit = sweep_report_unit(parameter);
  if (unit.empty()) return std::string(analysis::to_string(parameter));
  return fmt::format("{}_{}", analysis::to_string(parameter), unit);
}

std::string sweep_csv(const analysis::SweepResult& sweep) {
  std::string csv = fmt::format(
      "{},performance_index_per_um,status,deformation_um,cutting_depth_um,Q_um2,puncture_force_N,"
      "critical_buckling_load_N,buckling_force_N,reason\n",
      sweep_value_column(sweep.parameter));
  for (const analysis::SweepPoint& point : sweep.points) {
    const analysis::PerformanceIndexResult& r = point.result;
    csv += fmt::format("{:.10g},{:.10g},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{}\n",
                       report_value(sweep.parameter, point.value), per_um(r.performance_index),
                       analysis::to_string(r.status), um(r.deformation), um(r.cutting_depth), um2(r.q_factor),
                       r.puncture_force, r.buckling.critical_load, r.buckling_force, csv_field(r.reason));
  }
  return csv;
}

nlohmann::json sweep_json(const analysis::SweepResult& sweep) {
  const std::string column = sweep_value_column(sweep.parameter);
  nlohmann::json points = nlohmann::json::array();
  for (const analysis::SweepPoint& point : sweep.points) {
    points.push_back({{column, report_value(sweep.parameter, point.value)},
                      {"details", performance_json(point.design, point.result)}});
  }
  return {{"parameter", analysis::to_string(sweep.parameter)},
          {"unit", sweep_report_unit(sweep.parameter)},
          {"points", std::move(points)}};
}

void write_text_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, content);
}

}  // namespace needlekit::io
