// needlekit/patch: patch designs, placement, rigid / flexible / equilibrium fits and the per-needle evaluation
// (numpy arrays of per-needle quantities), patch case files and their CSV/JSON as the CLI writes them.
#include "common.hpp"
#include "enum_binding.hpp"
#include "parameters.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/io/patch_writers.hpp"
#include "needlekit/patch/fit_and_evaluate.hpp"
#include "needlekit/patch/fit_parameters.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/needle_evaluation.hpp"
#include "needlekit/patch/patch_design.hpp"
#include "needlekit/patch/patch_design_parameters.hpp"
#include "needlekit/patch/patch_placement.hpp"
#include "needlekit/patch/spring_geodesics.hpp"

namespace needlekit::python {
namespace {

using namespace patch;

// One per-needle quantity of an evaluation as a numpy array.
template <class T>
py::array_t<T> needle_column(const PatchEvaluation& e, T (*get)(const NeedleState&)) {
  std::vector<T> values;
  values.reserve(e.needles.size());
  for (const NeedleState& n : e.needles) values.push_back(get(n));
  return owning_array(std::move(values));
}

// A per-needle flag as a numpy bool array (stored as bytes: std::vector<bool> has no contiguous storage).
py::object needle_flags(const PatchEvaluation& e, bool (*get)(const NeedleState&)) {
  std::vector<std::uint8_t> values;
  values.reserve(e.needles.size());
  for (const NeedleState& n : e.needles) values.push_back(get(n));
  return owning_array(std::move(values)).attr("view")("bool");
}

py::array_t<double> needle_points(const PatchEvaluation& e, Eigen::Vector3d NeedleState::*member) {
  std::vector<double> values;
  for (const NeedleState& n : e.needles) values.insert(values.end(), (n.*member).data(), (n.*member).data() + 3);
  py::array_t<double> flat = owning_array(std::move(values));
  return flat.reshape({static_cast<py::ssize_t>(e.needles.size()), py::ssize_t{3}});
}

void bind_design_and_fit(py::module_& m) {
  py::class_<PatchDesignOptions> options(m, "PatchDesignOptions", "A Flexi-patch of n_h x n_v needles (§5.5).");
  options.def_readwrite("needle", &PatchDesignOptions::needle, "the needle at every node")
      .def_readwrite("material", &PatchDesignOptions::material, "the needles' material");
  def_parameters<PatchDesignOptions>(options, kPatchDesignParameters);  // every number; keyword init
  py::class_<PatchDesign>(m, "PatchDesign", "The grid, springs and needles of a patch (m).")
      .def_readonly("nodes_u", &PatchDesign::nodes_u)
      .def_readonly("nodes_v", &PatchDesign::nodes_v)
      .def_readonly("pitch_u", &PatchDesign::pitch_u, "m")
      .def_readonly("pitch_v", &PatchDesign::pitch_v, "m")
      .def_readonly("width_u", &PatchDesign::width_u, "m")
      .def_readonly("width_v", &PatchDesign::width_v, "m")
      .def_property_readonly(
          "rest_positions",
          [](py::object self) { return points_view(self.cast<const PatchDesign&>().rest_positions, self); },
          "m, (N, 2)")
      .def_readonly("inner", &PatchDesign::inner)
      .def_readonly("needle", &PatchDesign::needle)
      .def_readonly("material", &PatchDesign::material)
      .def("node_count", &PatchDesign::node_count);
  m.def("patch_design", &patch_design, py::arg("options"));

  bind_enum<kApproachNames>(m, "Approach", "The direction a patch approaches the surface from.");
  py::class_<Placement> placement(m, "Placement", "Where and how a patch is applied (§5.7).");
  def_keyword_init<Placement>(placement);
  placement.def_readwrite("center", &Placement::center, "m")
      .def_readwrite("center_vertex", &Placement::center_vertex)
      .def_readwrite("approach", &Placement::approach);
  def_quantity(placement, "rotation", &Placement::rotation, Dimension::Angle, "rad");
  def_quantity(placement, "max_center_distance", &Placement::max_center_distance, Dimension::Length, "m");
  def_quantity(placement, "approach_height", &Placement::approach_height, Dimension::Length, "m, 0: automatic");
  py::class_<PatchFrame>(m, "PatchFrame")
      .def_readonly("surface_point", &PatchFrame::surface_point, "m")
      .def_readonly("triangle", &PatchFrame::triangle)
      .def_readonly("approach", &PatchFrame::approach)
      .def_readonly("u", &PatchFrame::u)
      .def_readonly("v", &PatchFrame::v)
      .def_readonly("approach_height", &PatchFrame::approach_height, "m");
  m.def("patch_frame", &patch_frame, py::arg("surface"), py::arg("placement"), py::arg("patch_diagonal"),
        py::arg("needle_length"));

  bind_enum<kPatchKindNames>(m, "PatchKind", "How a patch is fitted to a surface (ch. 5).");
  bind_enum<kFirstNodeNames>(m, "FirstNode", "The node a flexible fit starts from (Alg 5.1).");
  bind_enum<kWalkMethodNames>(m, "WalkMethod", "How a flexible fit walks the surface between nodes.");
  // The rows of patch/fit_parameters.hpp: every field but the progress callbacks.
  py::class_<FlexibleFitOptions> flexible(m, "FlexibleFitOptions", "A flexible fit by node sweeping (Alg 5.1-5.3).");
  def_parameters<FlexibleFitOptions>(flexible, kFlexibleFitParameters);
  py::class_<EquilibriumFitOptions> equilibrium(m, "EquilibriumFitOptions",
                                                "The static equilibrium of the springs under a load per node.");
  def_parameters<EquilibriumFitOptions>(equilibrium, kEquilibriumFitParameters);
  py::class_<FitOptions> fit(m, "FitOptions", "How a patch is fitted: the kind and the options of each kind.");
  fit.def_readwrite("flexible", &FitOptions::flexible, "FlexibleFitOptions, used when kind is Flexible")
      .def_readwrite("equilibrium", &FitOptions::equilibrium, "EquilibriumFitOptions, used when kind is Equilibrium");
  def_parameters<FitOptions>(fit, kFitParameters);
  bind_enum<kFitStatusNames>(m, "FitStatus", "The outcome of a patch fit.");
  py::class_<FittedPatch>(m, "FittedPatch",
                          "A patch after fitting: node positions and normals as (N, 3) numpy views (m).")
      .def_property_readonly(
          "positions", [](py::object self) { return points_view(self.cast<const FittedPatch&>().positions, self); },
          "m, (N, 3)")
      .def_property_readonly(
          "normals", [](py::object self) { return points_view(self.cast<const FittedPatch&>().normals, self); },
          "(N, 3)")
      .def_readonly("on_surface", &FittedPatch::on_surface)
      .def_readonly("frame", &FittedPatch::frame)
      .def_readonly("status", &FittedPatch::status)
      .def_readonly("reason", &FittedPatch::reason)
      .def_readonly("affected_nodes", &FittedPatch::affected_nodes)
      .def_readonly("first_node", &FittedPatch::first_node)
      .def_readonly("iterations", &FittedPatch::iterations);
  m.def(
      "fit_patch",
      [](const geometry::SurfaceMesh& s, const PatchDesign& d, const PatchFrame& f, const FitOptions& o) {
        py::gil_scoped_release released;
        return fit_patch(s, d, f, o);
      },
      py::arg("surface"), py::arg("design"), py::arg("frame"), py::arg("options") = FitOptions{},
      "Fits the patch onto the surface: rigid (§6.4.1), flexible (Alg 5.1-5.3) or equilibrium.");
  m.def("spring_energies", &spring_energies, py::arg("design"), py::arg("positions"), "J per spring (Eq 5.13).");
}

void bind_evaluation(py::module_& m) {
  py::class_<NeedleEvaluationOptions> options(m, "NeedleEvaluationOptions");
  def_keyword_init<NeedleEvaluationOptions>(options);
  options.def_readwrite("conditions", &NeedleEvaluationOptions::conditions)
      .def_readwrite("index", &NeedleEvaluationOptions::index)
      .def_readwrite("local_pitch", &NeedleEvaluationOptions::local_pitch);
  py::class_<Statistics>(m, "Statistics")
      .def_readonly("min", &Statistics::min)
      .def_readonly("max", &Statistics::max)
      .def_readonly("mean", &Statistics::mean)
      .def_readonly("total", &Statistics::total)
      .def_readonly("count", &Statistics::count);
  py::class_<NeedleState>(m, "NeedleState", "One needle of a fitted patch (§5.2-5.3; SI).")
      .def_readonly("base", &NeedleState::base)
      .def_readonly("tip", &NeedleState::tip)
      .def_readonly("axis", &NeedleState::axis)
      .def_readonly("hits_surface", &NeedleState::hits_surface)
      .def_readonly("surface_point", &NeedleState::surface_point)
      .def_readonly("surface_normal", &NeedleState::surface_normal)
      .def_readonly("travel", &NeedleState::travel, "m, x (Eq 5.12)")
      .def_readonly("penetration", &NeedleState::penetration, "m, x - d")
      .def_readonly("angle", &NeedleState::angle, "rad")
      .def_readonly("buckling_force", &NeedleState::buckling_force, "N")
      .def_readonly("bending_force", &NeedleState::bending_force, "N")
      .def_readonly("penetrates", &NeedleState::penetrates)
      .def_readonly("buckles", &NeedleState::buckles)
      .def_readonly("bends", &NeedleState::bends)
      .def_readonly("local_pitch", &NeedleState::local_pitch, "m")
      .def_readonly("performance_index", &NeedleState::performance_index, "1/m")
      .def_readonly("status", &NeedleState::status);
  py::class_<PatchEvaluation>(m, "PatchEvaluation",
                              "Per-needle evaluation of a fitted patch; needle_arrays() gives numpy columns.")
      .def_readonly("needles", &PatchEvaluation::needles)
      .def_readonly("reference", &PatchEvaluation::reference)
      .def_readonly("penetrating", &PatchEvaluation::penetrating)
      .def_readonly("buckled", &PatchEvaluation::buckled)
      .def_readonly("bent", &PatchEvaluation::bent)
      .def_readonly("on_surface", &PatchEvaluation::on_surface)
      .def_readonly("buckling_force", &PatchEvaluation::buckling_force)
      .def_readonly("bending_force", &PatchEvaluation::bending_force)
      .def_readonly("angle", &PatchEvaluation::angle)
      .def_readonly("travel", &PatchEvaluation::travel)
      .def_readonly("performance_index", &PatchEvaluation::performance_index)
      .def_readonly("spring_energy", &PatchEvaluation::spring_energy)
      .def(
          "needle_arrays",
          [](const PatchEvaluation& e) {
            py::dict d;
            d["base"] = needle_points(e, &NeedleState::base);
            d["tip"] = needle_points(e, &NeedleState::tip);
            d["surface_point"] = needle_points(e, &NeedleState::surface_point);
            d["travel"] = needle_column<double>(e, [](const NeedleState& n) { return n.travel; });
            d["penetration"] = needle_column<double>(e, [](const NeedleState& n) { return n.penetration; });
            d["angle"] = needle_column<double>(e, [](const NeedleState& n) { return n.angle; });
            d["buckling_force"] = needle_column<double>(e, [](const NeedleState& n) { return n.buckling_force; });
            d["bending_force"] = needle_column<double>(e, [](const NeedleState& n) { return n.bending_force; });
            d["performance_index"] = needle_column<double>(e, [](const NeedleState& n) { return n.performance_index; });
            d["local_pitch"] = needle_column<double>(e, [](const NeedleState& n) { return n.local_pitch; });
            d["hits_surface"] = needle_flags(e, [](const NeedleState& n) { return n.hits_surface; });
            d["penetrates"] = needle_flags(e, [](const NeedleState& n) { return n.penetrates; });
            d["buckles"] = needle_flags(e, [](const NeedleState& n) { return n.buckles; });
            d["bends"] = needle_flags(e, [](const NeedleState& n) { return n.bends; });
            py::list status;
            for (const NeedleState& n : e.needles) status.append(n.status);
            d["status"] = status;
            return d;
          },
          "Per-needle numpy arrays (SI): base, tip, surface_point (N, 3); travel, penetration, angle, forces, "
          "performance_index, local_pitch (N); flags; status names.");
  m.def(
      "evaluate_needles",
      [](const geometry::SurfaceMesh& s, const PatchDesign& d, const FittedPatch& f, const NeedleEvaluationOptions& o) {
        py::gil_scoped_release released;
        return evaluate_needles(s, d, f, o);
      },
      py::arg("surface"), py::arg("design"), py::arg("fit"), py::arg("options") = NeedleEvaluationOptions{},
      "Every needle of a fitted patch (§5.2-5.3, §6.4).");
  py::class_<SpringGeodesics>(m, "SpringGeodesics")
      .def_readonly("strain", &SpringGeodesics::strain)
      .def_readonly("not_converged", &SpringGeodesics::not_converged);
  m.def("spring_geodesics", &spring_geodesics, py::arg("surface"), py::arg("design"), py::arg("fit"),
        "The springs measured along the surface (geodesic distances).");

  py::class_<io::PatchCase>(m, "PatchCase", "A patch case file (`needlekit patch CASE.toml`).")
      .def_readwrite("mesh", &io::PatchCase::mesh)
      .def_readwrite("mesh_unit", &io::PatchCase::mesh_unit, "m per file unit")
      .def_readwrite("placement", &io::PatchCase::placement)
      .def_readwrite("design", &io::PatchCase::design)
      .def_readwrite("fit", &io::PatchCase::fit)
      .def_readwrite("load_given", &io::PatchCase::load_given)
      .def_readwrite("evaluation", &io::PatchCase::evaluation);
  m.def("read_patch_case", &io::read_patch_case, py::arg("path"),
        "Reads a patch case file; raises InvalidInput / IoError naming file, line and key.");
  m.def("patch_needles_csv", &io::patch_needles_csv, py::arg("design"), py::arg("fit"), py::arg("evaluation"));
  m.def(
      "patch_summary_json",
      [](const PatchDesign& d, const FitOptions& o, const FittedPatch& f, const PatchEvaluation& e, double fit_ms) {
        return to_python(io::patch_summary_json(d, o, f, e, fit_ms));
      },
      py::arg("design"), py::arg("fit_options"), py::arg("fit"), py::arg("evaluation"), py::arg("fit_ms") = 0.0,
      "The summary of `needlekit patch --json` (units in the keys).");
}

void bind_fit_and_evaluate(py::module_& m) {
  py::class_<FitAndEvaluateOptions> options(m, "FitAndEvaluateOptions", "Placement, fit and evaluation of a patch.");
  def_keyword_init<FitAndEvaluateOptions>(options);
  options.def_readwrite("placement", &FitAndEvaluateOptions::placement)
      .def_readwrite("fit", &FitAndEvaluateOptions::fit)
      .def_readwrite("evaluation", &FitAndEvaluateOptions::evaluation)
      .def_readwrite("spring_geodesics", &FitAndEvaluateOptions::spring_geodesics);
  py::class_<FitAndEvaluateResult>(m, "FitAndEvaluateResult")
      .def_readonly("status", &FitAndEvaluateResult::status)
      .def_readonly("reason", &FitAndEvaluateResult::reason)
      .def_readonly("design", &FitAndEvaluateResult::design)
      .def_readonly("frame", &FitAndEvaluateResult::frame)
      .def_readonly("fit", &FitAndEvaluateResult::fit)
      .def_readonly("evaluation", &FitAndEvaluateResult::evaluation)
      .def_readonly("geodesics", &FitAndEvaluateResult::geodesics)
      .def_readonly("fit_seconds", &FitAndEvaluateResult::fit_seconds, "s");
  m.def(
      "fit_and_evaluate",
      [](const geometry::SurfaceMesh& s, const PatchDesignOptions& d, FitAndEvaluateOptions o, py::object progress) {
        ProgressRelay relay(std::move(progress));
        o.progress = [&relay](double fraction) { return relay.keep_going(fraction); };
        try {
          py::gil_scoped_release released;
          return fit_and_evaluate(s, d, o);
        } catch (const Interrupted&) {
          relay.rethrow();  // the callback's exception (KeyboardInterrupt on Ctrl-C)
          throw;
        }
      },
      py::arg("surface"), py::arg("design"), py::arg("options") = FitAndEvaluateOptions{},
      py::arg("progress") = py::none(),
      "The patch pipeline (ch. 5, §6.4): design, frame, fit, every needle evaluated; what `needlekit patch` runs. "
      "progress(fraction) is called after the frame, each node mapped or Newton iteration of the fit, the evaluation; "
      "an exception it raises (or Ctrl-C) stops the fit and propagates.");
}

}  // namespace

void bind_patch(py::module_& m) {
  bind_design_and_fit(m);
  bind_evaluation(m);
  bind_fit_and_evaluate(m);
}

}  // namespace needlekit::python
