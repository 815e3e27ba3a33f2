// needlekit/analysis: the puncture model, buckling, the performance index (evaluate), the design optimizer
// (optimize) and the sensitivity sweep (sweep), with their JSON as the CLI writes it.
#include <fmt/format.h>

#include "common.hpp"
#include "enum_binding.hpp"
#include "needlekit/analysis/bending.hpp"
#include "needlekit/analysis/buckling.hpp"
#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/analysis/design_space.hpp"
#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/analysis/puncture_force_law.hpp"
#include "needlekit/analysis/puncture_model.hpp"
#include "needlekit/analysis/sensitivity_sweep.hpp"
#include "needlekit/io/result_writers.hpp"
#include "needlekit/materials/needle_material.hpp"

namespace needlekit::python {
namespace {

using namespace analysis;

// A material given as a preset name or a NeedleMaterial.
materials::NeedleMaterial material_of(py::handle value) {
  if (py::isinstance<py::str>(value)) return materials::material_preset(value.cast<std::string>());
  return value.cast<materials::NeedleMaterial>();
}
// A tissue given as "skin" | "brain" or a PunctureModel.
PunctureModel tissue_of(py::handle value) {
  if (py::isinstance<py::str>(value)) return puncture_model_preset(value.cast<std::string>(), "tissue");
  return value.cast<PunctureModel>();
}

// A grid range from a GridRange or (min, max, step) quantities of `dimension`.
GridRange range_of(py::handle value, Dimension dimension, const std::string& what) {
  if (py::isinstance<GridRange>(value)) return value.cast<GridRange>();
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::len(value) != 3) {
    throw_invalid(what + ": expected a GridRange or (min, max, step)");
  }
  const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
  return {quantity(items[0], dimension, what + "[0]"), quantity(items[1], dimension, what + "[1]"),
          quantity(items[2], dimension, what + "[2]")};
}

template <class Class>
void def_range(Class& cls, const char* name, GridRange DesignSpace::*member, Dimension dimension, const char* doc) {
  cls.def_property(
      name, [member](const DesignSpace& s) { return s.*member; },
      [member, dimension, name](DesignSpace& s, py::handle value) { s.*member = range_of(value, dimension, name); },
      doc);
}

void bind_puncture_and_buckling(py::module_& m) {
  bind_enum<kPunctureForceLawKindNames>(m, "PunctureForceLawKind", "The puncture-force laws ([tissue] puncture_force).");
  py::class_<PunctureForceLaw> law(m, "PunctureForceLaw",
                                   "The puncture force F(A) of the analytic engine ([tissue] puncture_force).");
  def_keyword_init<PunctureForceLaw>(law);
  law.def_readwrite("kind", &PunctureForceLaw::kind);
  law.def_readwrite("slope", &PunctureForceLaw::slope, "N/m^2 (area laws) or N/m (diameter laws), SI");
  def_quantity(law, "intercept", &PunctureForceLaw::intercept, Dimension::Force, "N, intercept of the linear laws");
  law.def_readwrite("table_tip_diameter", &PunctureForceLaw::table_tip_diameter, "m, table law's tip diameters");
  law.def_readwrite("table_force", &PunctureForceLaw::table_force, "N, table law's forces");
  def_quantity(law, "valid_min_tip_diameter", &PunctureForceLaw::valid_min_tip_diameter, Dimension::Length,
               "m, smallest equivalent tip diameter the law was measured on");
  law.def_readwrite("valid_max_tip_diameter", &PunctureForceLaw::valid_max_tip_diameter,
                    "m or None, largest equivalent tip diameter the law was measured on");
  m.def("puncture_force_law_preset", &puncture_force_law_preset, py::arg("kind"));

  py::class_<PunctureModel> model(m, "PunctureModel", "The tissue's puncture model (§4.2, Eqs 4.1-4.3).");
  def_keyword_init<PunctureModel>(model);
  model.def_readwrite("name", &PunctureModel::name);
  def_quantity(model, "alpha", &PunctureModel::alpha, Dimension::Force, "N, alpha of F(d) = alpha*exp(tau*d) (Eq 4.1)");
  def_quantity(model, "tau", &PunctureModel::tau, Dimension::InverseLength, "1/m, tau (6.25 /mm for skin)");
  model.def_readwrite("force_law", &PunctureModel::force_law, "F(A): Eq 4.2 by default");
  def_quantity(model, "small_tip_slope", &PunctureModel::small_tip_slope, Dimension::InverseLength,
               "1/m, K of the small-tip branch d = K*A");
  m.def("skin_puncture_model", &skin_puncture_model);
  m.def("brain_puncture_model", &brain_puncture_model);
  m.def("puncture_model_preset", &puncture_model_preset, py::arg("name"), py::arg("what") = "tissue.model");
  m.def("puncture_force", py::overload_cast<double, const PunctureModel&>(&puncture_force), py::arg("tip_area"), py::arg("model"), "F(A) in N, signed (Eq 4.2).");
  py::class_<SkinDeformation>(m, "SkinDeformation")
      .def_readonly("depth", &SkinDeformation::depth, "m, d")
      .def_readonly("small_tip_branch", &SkinDeformation::small_tip_branch);
  m.def("skin_deformation", &skin_deformation, py::arg("tip_area"), py::arg("model"), "d of Eq 4.3.");
  m.def("small_tip_area_limit", &small_tip_area_limit, py::arg("model"), "m^2");

  bind_enum<kEndConditionNames>(m, "EndCondition", "How the needle's column is held at its ends (§2.5).");
  bind_enum<kEffectiveLengthNames>(m, "EffectiveLengthValue", "The effective-length factors K of the end conditions: theoretical or practical (Mott 2008).");
  bind_enum<kBucklingMethodNames>(m, "BucklingMethod", "How the critical buckling load was obtained.");
  py::class_<BucklingOptions> buckling(m, "BucklingOptions", "End condition and column formulas (§2.5).");
  def_keyword_init<BucklingOptions>(buckling);
  buckling.def_readwrite("end_condition", &BucklingOptions::end_condition)
      .def_readwrite("effective_length", &BucklingOptions::effective_length)
      .def_readwrite("johnson_for_short_columns", &BucklingOptions::johnson_for_short_columns);
  py::class_<BucklingResult>(m, "BucklingResult", "Critical buckling load and how it was obtained.")
      .def_readonly("critical_load", &BucklingResult::critical_load, "N, P_cr")
      .def_readonly("method", &BucklingResult::method)
      .def_readonly("tapered_factor", &BucklingResult::tapered_factor, "m of Eq 2.36")
      .def_readonly("slenderness_ratio", &BucklingResult::slenderness_ratio, "L_e/r")
      .def_readonly("column_constant", &BucklingResult::column_constant, "C_c (0: no yield strength)")
      .def_readonly("note", &BucklingResult::note);
  m.def(
      "critical_buckling_load",
      [](const needle::NeedleGeometry& n, py::handle material, const BucklingOptions& o) {
        return critical_buckling_load(n, material_of(material), o);
      },
      py::arg("needle"), py::arg("material"), py::arg("options") = BucklingOptions{},
      "P_cr of a needle (Euler, Johnson, or the tapered-column eigenvalue); material: a preset name or "
      "NeedleMaterial.");
  m.def("tapered_column_factor", &tapered_column_factor, py::arg("needle"),
        py::arg("end_condition") = EndCondition::FixedFree, "m of P_cr = m*E*I2/L^2 (Eq 2.36), dimensionless.");
  m.def("critical_bending_load", &critical_bending_load, py::arg("needle"), py::arg("allowable_stress"),
        "P_Be in N (Eqs 5.7/5.8); allowable_stress in Pa.");
}

void bind_performance_index(py::module_& m) {
  py::class_<ArrayDesign> design(m, "ArrayDesign", "A square array of n x n identical needles on a patch of width w.");
  def_keyword_init<ArrayDesign>(design);
  design.def_readwrite("needle", &ArrayDesign::needle)
      .def_property(
          "material", [](const ArrayDesign& d) { return d.material; },
          [](ArrayDesign& d, py::handle value) { d.material = material_of(value); },
          "NeedleMaterial, or a preset name (\"silicon\")")
      .def_readwrite("needles_per_row", &ArrayDesign::needles_per_row, "n >= 1");
  def_quantity(design, "width", &ArrayDesign::width, Dimension::Length, "m, w > 0");

  py::class_<InsertionConditions> conditions(m, "InsertionConditions", "Tissue, angle and target depth.");
  def_keyword_init<InsertionConditions>(conditions);
  conditions.def_property(
      "tissue", [](const InsertionConditions& c) { return c.tissue; },
      [](InsertionConditions& c, py::handle value) { c.tissue = tissue_of(value); },
      "PunctureModel, or \"skin\" | \"brain\"");
  def_quantity(conditions, "angle", &InsertionConditions::angle, Dimension::Angle, "rad, [0, pi/2)");
  def_quantity(conditions, "target_depth", &InsertionConditions::target_depth, Dimension::Length, "m, T > 0");

  py::class_<PerformanceIndexOptions> options(m, "PerformanceIndexOptions");
  def_keyword_init<PerformanceIndexOptions>(options);
  options.def_readwrite("buckling", &PerformanceIndexOptions::buckling)
      .def_readwrite("buckling_safety_factor", &PerformanceIndexOptions::buckling_safety_factor, ">= 1")
      .def_readwrite("bending_safety_factor", &PerformanceIndexOptions::bending_safety_factor, ">= 1")
      .def_readwrite("gap_ratio", &PerformanceIndexOptions::gap_ratio, "delta of Eqs 4.20-4.24")
      .def_readwrite("spacing_factor", &PerformanceIndexOptions::spacing_factor, "beta of w >= beta*n*D2");
  def_optional_quantity(options, "index_pitch", &PerformanceIndexOptions::index_pitch, Dimension::Length,
                        "m, pitch used in the index (None: w/n)");

  bind_enum<kPerformanceStatusNames>(m, "PerformanceStatus", "The outcome of one evaluation of the performance index.");
  m.def(
      "performance_status_name", [](PerformanceStatus s) { return std::string(to_string(s)); }, py::arg("status"),
      "\"ok\", \"constraint_violated\", \"too_short\", \"buckles\", \"bends\"");

  using R = PerformanceIndexResult;
  py::class_<R>(m, "PerformanceIndexResult", "Every quantity of one evaluation (SI: m, m^2, m^3, N, 1/m).")
      .def_readonly("tip_area", &R::tip_area, "m^2, A")
      .def_readonly("puncture_force", &R::puncture_force, "N, F(A) (Eq 4.2), signed")
      .def_readonly("deformation", &R::deformation, "m, d (Eq 4.3)")
      .def_readonly("small_tip_branch", &R::small_tip_branch)
      .def_readonly("cutting_depth", &R::cutting_depth, "m, h = L - d")
      .def_readonly("permeation_depth", &R::permeation_depth, "m, H (Eq 4.23)")
      .def_readonly("diameter_at_surface", &R::diameter_at_surface, "m, b")
      .def_readonly("embedded_volume", &R::embedded_volume, "m^3 (Table 4.2)")
      .def_readonly("q_factor", &R::q_factor, "m^2, Q (Table 4.4)")
      .def_readonly("hole_volume", &R::hole_volume, "m^3")
      .def_readonly("gap_volume", &R::gap_volume, "m^3")
      .def_readonly("pitch", &R::pitch, "m, w/n")
      .def_readonly("fractional_skin_volume", &R::fractional_skin_volume, "f_v")
      .def_readonly("needle_volume", &R::needle_volume, "m^3")
      .def_readonly("buckling", &R::buckling)
      .def_readonly("buckling_force", &R::buckling_force, "N, |F|/cos(theta)")
      .def_readonly("critical_bending_load", &R::critical_bending_load, "N, P_Be or None")
      .def_readonly("bending_force", &R::bending_force, "N, |F|*tan(theta)")
      .def_readonly("buckling_ok", &R::buckling_ok, "phi")
      .def_readonly("bending_ok", &R::bending_ok, "omega or None (not assessed)")
      .def_readonly("performance_index", &R::performance_index, "1/m (x 1e-6 for the dissertation's 1/um)")
      .def_readonly("status", &R::status)
      .def_readonly("failed_checks", &R::failed_checks, "bit 1 << PerformanceStatus of every failed check")
      .def_readonly("reason", &R::reason)
      .def_readonly("notes", &R::notes);
  m.def(
      "performance_index",
      [](const ArrayDesign& d, const InsertionConditions& c, const PerformanceIndexOptions& o) {
        return performance_index(d, c, o);
      },
      py::arg("design"), py::arg("conditions") = InsertionConditions{}, py::arg("options") = PerformanceIndexOptions{},
      "The performance index of one array with every intermediate quantity (Eqs 4.25, 5.9); what `needlekit "
      "evaluate` computes. Raises InvalidInput for an invalid design.");
  // The JSON writers return dicts (the CLI's --json, number for number).
  m.def(
      "performance_json", [](const ArrayDesign& d, const R& r) { return to_python(io::performance_json(d, r)); },
      py::arg("design"), py::arg("result"),
      "The result as the CLI's `evaluate --json` prints it (units in the keys: um, um2, N, GPa, 1/um).");
}

void bind_optimizer(py::module_& m) {
  py::class_<GridRange> range(m, "GridRange", "An inclusive grid min, min + step, ..., <= max (SI).");
  def_keyword_init<GridRange>(range);
  range
      .def(py::init([](double min, double max, double step) {
             return GridRange{min, max, step};
           }),
           py::arg("min"), py::arg("max"), py::arg("step"))
      .def_readwrite("min", &GridRange::min)
      .def_readwrite("max", &GridRange::max)
      .def_readwrite("step", &GridRange::step);
  m.def("grid_values", &grid_values, py::arg("range"), py::arg("key") = "range");

  py::class_<DesignSpace> space(m, "DesignSpace",
                                "A grid of n, D1, D2, D3, w, L for one needle type (§4.8, Fig 6.20). Ranges accept "
                                "GridRange or (min, max, step) quantities, e.g. (\"30 um\", \"150 um\", \"10 um\").");
  def_keyword_init<DesignSpace>(space);
  space
      .def_property(
          "shape", [](const DesignSpace& s) { return s.shape; },
          [](DesignSpace& s, py::handle v) {
            s.shape =
                py::isinstance<py::str>(v) ? needle::shape_from_string(v.cast<std::string>()) : v.cast<needle::Shape>();
          })
      .def_readwrite("hollow", &DesignSpace::hollow)
      .def_property(
          "material", [](const DesignSpace& s) { return s.material; },
          [](DesignSpace& s, py::handle v) { s.material = material_of(v); })
      .def_readwrite("conditions", &DesignSpace::conditions)
      .def_readwrite("spacing_factor", &DesignSpace::spacing_factor);
  def_range(space, "needles_per_row", &DesignSpace::needles_per_row, Dimension::Dimensionless, "n");
  def_range(space, "tip_diameter", &DesignSpace::tip_diameter, Dimension::Length, "m, D1");
  def_range(space, "base_diameter", &DesignSpace::base_diameter, Dimension::Length, "m, D2");
  def_range(space, "bore_diameter", &DesignSpace::bore_diameter, Dimension::Length, "m, D3");
  def_range(space, "width", &DesignSpace::width, Dimension::Length, "m, w");
  def_range(space, "length", &DesignSpace::length, Dimension::Length, "m, L");
  m.def("figure_6_20_space", &figure_6_20_space, py::arg("shape"), py::arg("hollow"),
        "The dissertation's Fig 6.20 grid for one needle type (silicon, skin, T = 50 um, beta = 3).");
  m.def("design_space_size", &design_space_size, py::arg("space"));

  bind_enum<kSearchMethodNames>(m, "SearchMethod", "How the optimizer searches the design space.");
  py::class_<OptimizerOptions> options(m, "OptimizerOptions");
  def_keyword_init<OptimizerOptions>(options);
  options.def_readwrite("method", &OptimizerOptions::method)
      .def_readwrite("top", &OptimizerOptions::top, "designs to report (brute force), >= 1")
      .def_readwrite("published_compat", &OptimizerOptions::published_compat)
      .def_readwrite("threads", &OptimizerOptions::threads, "0: all cores")
      .def_readwrite("buckling", &OptimizerOptions::buckling)
      .def_readwrite("buckling_safety_factor", &OptimizerOptions::buckling_safety_factor)
      .def_readwrite("max_brute_force_points", &OptimizerOptions::max_brute_force_points);
  py::class_<DesignCandidate>(m, "DesignCandidate", "One design of the optimizer's top list (SI).")
      .def_readonly("needles_per_row", &DesignCandidate::needles_per_row)
      .def_readonly("tip_diameter", &DesignCandidate::tip_diameter, "m")
      .def_readonly("base_diameter", &DesignCandidate::base_diameter, "m")
      .def_readonly("bore_diameter", &DesignCandidate::bore_diameter, "m")
      .def_readonly("width", &DesignCandidate::width, "m")
      .def_readonly("length", &DesignCandidate::length, "m")
      .def_readonly("performance_index", &DesignCandidate::performance_index, "1/m")
      .def_readonly("details", &DesignCandidate::details);
  bind_enum<kOptimizerStatusNames>(m, "OptimizerStatus", "The outcome of an optimization.");
  py::class_<OptimizerResult>(m, "OptimizerResult")
      .def_readonly("status", &OptimizerResult::status)
      .def_readonly("reason", &OptimizerResult::reason)
      .def_readonly("top", &OptimizerResult::top, "best first")
      .def_readonly("grid_points", &OptimizerResult::grid_points)
      .def_readonly("evaluated", &OptimizerResult::evaluated)
      .def_readonly("feasible", &OptimizerResult::feasible)
      .def_readonly("needle_evaluations", &OptimizerResult::needle_evaluations)
      .def_readonly("seconds", &OptimizerResult::seconds, "s, wall time");
  m.def(
      "optimize_design",
      [](const DesignSpace& space, OptimizerOptions options, py::object progress) {
        ProgressRelay relay(std::move(progress));
        options.progress = [&relay](double fraction) { return relay.keep_going(fraction); };
        OptimizerResult result;
        {
          py::gil_scoped_release released;
          result = optimize_design(space, options);
        }
        relay.rethrow();
        return result;
      },
      py::arg("space"), py::arg("options") = OptimizerOptions{}, py::arg("progress") = py::none(),
      "The design of the space with the largest performance index (§4.8); what `needlekit optimize` does. "
      "progress(fraction) is called now and then; Ctrl-C stops the search (KeyboardInterrupt).");
  m.def(
      "optimizer_json",
      [](const DesignSpace& s, const OptimizerResult& r) { return to_python(io::optimizer_json(s, r)); },
      py::arg("space"), py::arg("result"), "The result as `needlekit optimize --json` prints it.");
}

void bind_sweep(py::module_& m) {
  bind_enum<kSweepParameterNames>(m, "SweepParameter", "The design parameter a sensitivity sweep varies.");
  m.def("sweep_parameter_from_string", &sweep_parameter_from_string, py::arg("text"), py::arg("what") = "parameter");
  m.def("sweep_parameter_dimension", &sweep_parameter_dimension, py::arg("parameter"));
  py::class_<SweepOptions> options(m, "SweepOptions",
                                   "One parameter varied from `from_` to `to` by `step` (quantities in the parameter's "
                                   "dimension: set `parameter` first when giving strings).");
  def_keyword_init<SweepOptions>(options);
  auto def_bound = [&options](const char* name, double SweepOptions::*member) {
    options.def_property(
        name, [member](const SweepOptions& o) { return o.*member; },
        [member, name](SweepOptions& o, py::handle v) {
          o.*member = quantity(v, sweep_parameter_dimension(o.parameter), name);
        });
  };
  options.def_property(
      "parameter", [](const SweepOptions& o) { return o.parameter; },
      [](SweepOptions& o, py::handle v) {
        o.parameter = py::isinstance<py::str>(v) ? sweep_parameter_from_string(v.cast<std::string>(), "parameter")
                                                 : v.cast<SweepParameter>();
      },
      "SweepParameter or its name (\"base_diameter\", ...)");
  def_bound("from_", &SweepOptions::from);
  def_bound("to", &SweepOptions::to);
  def_bound("step", &SweepOptions::step);
  py::class_<SweepPoint>(m, "SweepPoint")
      .def_readonly("value", &SweepPoint::value, "SI value of the varied parameter")
      .def_readonly("design", &SweepPoint::design)
      .def_readonly("conditions", &SweepPoint::conditions)
      .def_readonly("result", &SweepPoint::result);
  py::class_<SweepResult>(m, "SweepResult")
      .def_readonly("parameter", &SweepResult::parameter)
      .def_readonly("points", &SweepResult::points);
  m.def("sensitivity_sweep", &sensitivity_sweep, py::arg("design"), py::arg("conditions"), py::arg("options"),
        py::arg("sweep"), "One-at-a-time sensitivity of the index (Figs 6.18, 6.19); what `needlekit sweep` does.");
  m.def(
      "sweep_json", [](const SweepResult& s) { return to_python(io::sweep_json(s)); }, py::arg("sweep"));
  m.def("sweep_csv", &io::sweep_csv, py::arg("sweep"), "The CSV of `needlekit sweep --csv` (units in the header).");
}

}  // namespace

void bind_analysis(py::module_& m) {
  bind_puncture_and_buckling(m);
  bind_performance_index(m);
  bind_optimizer(m);
  bind_sweep(m);
}

}  // namespace needlekit::python
