// needlekit/insertion: indentation cases and runs (progress callbacks, GIL released, Ctrl-C stops the run, optional
// ParaView output), puncture points, post-puncture loads and the complete insertion curve.
#include "common.hpp"
#include "enum_binding.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/insertion/puncture_parameters.hpp"
#include "parameters.hpp"
#include "needlekit/insertion/complete_insertion.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/loading_parameters.hpp"
#include "needlekit/insertion/insertion_curve.hpp"
#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/insertion/insertion_curve_parameters.hpp"
#include "needlekit/insertion/post_puncture_parameters.hpp"
#include "needlekit/insertion/triangle_classification_parameters.hpp"
#include "needlekit/io/force_curve_csv.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/indentation_output.hpp"
#include "needlekit/io/insertion_case.hpp"
#include "needlekit/io/insertion_output.hpp"

namespace needlekit::python {
namespace {

using namespace insertion;

template <class T, class Member>
py::array_t<double> step_column(const IndentationResult& r, Member member) {
  std::vector<double> values;
  values.reserve(r.steps.size());
  for (const IndentationStep& s : r.steps) values.push_back(static_cast<double>(s.*member));
  return owning_array(std::move(values));
}

void bind_indentation(py::module_& m) {
  bind_enum<kPunctureCriterionNames>(m, "PunctureCriterion", "The criterion that decides puncture in an FE run (§3.5).");
  bind_enum<kPunctureLawNames>(m, "PunctureLaw",
                               "The puncture law of an FE run: the dissertation's criteria or the averaged contact "
                               "pressure.");
  py::class_<PuncturePoint> point(m, "PuncturePoint");
  def_keyword_init<PuncturePoint>(point);
  def_quantity(point, "depth", &PuncturePoint::depth, Dimension::Length, "m");
  def_quantity(point, "force", &PuncturePoint::force, Dimension::Force, "N");
  point.def_readwrite("criterion", &PuncturePoint::criterion);
  bind_needle_outcomes(m);
  py::class_<ForceDepthCurve>(m, "ForceDepthCurve", "Samples of depth (m) and force (N).")
      .def(py::init([](py::handle depth, py::handle force) {
             return ForceDepthCurve{values_from(depth, "depth"), values_from(force, "force")};
           }),
           py::arg("depth"), py::arg("force"))
      .def_property_readonly(
          "depth", [](py::object self) { return values_view(self.cast<const ForceDepthCurve&>().depth, self); }, "m")
      .def_property_readonly(
          "force", [](py::object self) { return values_view(self.cast<const ForceDepthCurve&>().force, self); }, "N");
  py::class_<PrePunctureCurve>(m, "PrePunctureCurve")
      .def(py::init([](const ForceDepthCurve& c, std::optional<PuncturePoint> p) {
             return PrePunctureCurve{c, p};
           }),
           py::arg("curve"), py::arg("puncture") = py::none())
      .def_readonly("curve", &PrePunctureCurve::curve)
      .def_readonly("puncture", &PrePunctureCurve::puncture);
  m.def("read_force_curve_csv", &io::read_force_curve_csv, py::arg("path"), "depth_<unit>,force_<unit> columns.");

  py::class_<PunctureOptions> puncture(m, "PunctureOptions",
                                        "Puncture criteria: the dissertation's (§3.5) or the averaged contact pressure; "
                                        "critical_pressure, toughness None: not used.");
  def_parameters<PunctureOptions>(puncture, kPunctureParameters);  // every field; keyword init

  using fem::SolverOptions;
  bind_enum<fem::kMaterialLawNames>(m, "MaterialLaw", "The hyperelastic law of a tissue layer.");
  bind_enum<fem::kElementOrderNames>(m, "ElementOrder", "Linear (4-node) or quadratic (10-node) tetrahedra.");
  bind_enum<fem::kContactModelNames>(m, "ContactModel", "How the needle touches the tissue.");
  bind_enum<fem::kLinearSolverNames>(m, "LinearSolver", "The linear solve of each Newton iteration.");
  bind_enum<fem::kBoundaryConditionNames>(m, "BoundaryCondition", "How the tissue block is held.");
  bind_enum<fem::kVolumetricFormulationNames>(m, "VolumetricFormulation", "How the volumetric part of the neo-Hookean law is integrated.");
  bind_enum<fem::kSolverBackendNames>(m, "SolverBackend", "Where the linear solves run.");
  py::class_<SolverOptions> solver(m, "SolverOptions", "The FE solver's law, elements, contact and tolerances (§3.4).");
  def_parameters<SolverOptions>(solver, fem::kSolverParameters);  // every field but the progress callback

  py::class_<NeedleSite> site(m, "NeedleSite");
  def_keyword_init<NeedleSite>(site);
  site.def_readwrite("position", &NeedleSite::position, "m, (x, y)");
  def_quantity(site, "tip_height", &NeedleSite::tip_height, Dimension::Length, "m, >= 0");
  py::class_<IndentationCase> indentation(
      m, "IndentationCase", "An indentation case (`needlekit indent`); read one with read_indentation_case.");
  def_keyword_init<IndentationCase>(indentation);
  indentation.def_readwrite("name", &IndentationCase::name)
      .def_readwrite("needle", &IndentationCase::needle)
      .def_readwrite("geometry", &IndentationCase::geometry)
      .def_readwrite("needles", &IndentationCase::needles)
      .def_readwrite("array", &IndentationCase::array, "a NeedleArray: `needles` then holds the whole array")
      .def_readwrite("block", &IndentationCase::block)
      .def_readwrite("tissue_mesh", &IndentationCase::tissue_mesh)
      .def_readwrite("solver", &IndentationCase::solver)
      .def_readwrite("puncture", &IndentationCase::puncture)
      .def_readwrite("edge_radius", &IndentationCase::edge_radius,
                     "m, surface contact on a parametric needle: its edges rounded with this radius (None: the "
                     "default, 2 um or half the largest the tip allows)");
  // [loading]: the rows of insertion::kLoadingParameters.
  indentation.doc() = std::string(py::str(indentation.doc())) + "\n\n[loading] keywords:" +
                      def_parameter_properties<Loading>(indentation, kLoadingParameters);
  indentation.def_readwrite("material", &IndentationCase::material,
                            "NeedleMaterial or None: for the bending check of the lateral load (Eqs 5.7/5.8)");
  m.def("read_indentation_case", &io::read_indentation_case, py::arg("path"),
        "Reads an indentation case file; raises InvalidInput naming file, line and key.");
  m.def(
      "validate_indentation_case", [](const IndentationCase& c) { validate(c); }, py::arg("case"));

  bind_enum<kIndentationStatusNames>(m, "IndentationStatus", "The outcome of an indentation run.");
  bind_enum<fem::kStartBalanceNames>(m, "StartBalance", "How a rezoned mesh came to equilibrium from its transferred state.");
  py::class_<IndentationProgress>(m, "IndentationProgress")
      .def_readonly("stage", &IndentationProgress::stage)
      .def_readonly("step", &IndentationProgress::step)
      .def_readonly("steps", &IndentationProgress::steps)
      .def_readonly("depth", &IndentationProgress::depth, "m")
      .def_readonly("fraction", &IndentationProgress::fraction);
  py::class_<IndentationStep>(m, "IndentationStep")
      .def_readonly("depth", &IndentationStep::depth, "m")
      .def_readonly("force", &IndentationStep::force, "N")
      .def_readonly("needle_force", &IndentationStep::needle_force, "N per needle")
      .def_readonly("contact_area", &IndentationStep::contact_area, "m^2")
      .def_readonly("contact_pressure", &IndentationStep::contact_pressure, "Pa")
      .def_readonly("max_contact_pressure", &IndentationStep::max_contact_pressure, "Pa")
      .def_readonly("averaged_pressure", &IndentationStep::averaged_pressure,
                    "Pa, the averaged-pressure law's p_l (0 under the dissertation's)")
      .def_readonly("needle_averaged_pressure", &IndentationStep::needle_averaged_pressure, "Pa per needle")
      .def_readonly("contact_nodes", &IndentationStep::contact_nodes)
      .def_readonly("strain_energy", &IndentationStep::strain_energy, "J")
      .def_readonly("external_work", &IndentationStep::external_work, "J")
      .def_readonly("newton_iterations", &IndentationStep::newton_iterations)
      .def_readonly("min_volume_ratio", &IndentationStep::min_volume_ratio,
                    "the most compressed tetrahedron's J = det F (below 0.3: forces depend on the mesh)")
      .def_readonly("tip_embedded_depth", &IndentationStep::tip_embedded_depth,
                    "m, how far the needles' tips lie inside the tissue past its top surface (surface contact)")
      .def_readonly("step_seconds", &IndentationStep::step_seconds, "s")
      .def_readonly("lateral_force", &IndentationStep::lateral_force,
                    "N, the tissue's force on the needles across their axis, block axes (x, y, z)")
      .def_readonly("moment", &IndentationStep::moment,
                    "N m, the tissue's moment on the needles about each needle's base centre, block axes");
  py::class_<BendingCheck>(m, "BendingCheck", "The ch. 4 bending check (Eqs 5.7/5.8) of the last step's lateral load.")
      .def_readonly("lateral_load", &BendingCheck::lateral_load, "N")
      .def_readonly("critical_load", &BendingCheck::critical_load, "N")
      .def_readonly("margin", &BendingCheck::margin, "critical_load / lateral_load (>= 1: safe)");
  py::class_<Remesh>(m, "Remesh", "One rezoning of the tissue (SolverOptions.rezone): where, why, what it changed.")
      .def_readonly("step", &Remesh::step, "the load step after which it happened")
      .def_readonly("depth", &Remesh::depth, "m")
      .def_readonly("reason", &Remesh::reason)
      .def_readonly("failure", &Remesh::failure, "empty, or why the rezoning failed (the run went on without it)")
      .def_readonly("elements_before", &Remesh::elements_before)
      .def_readonly("elements_after", &Remesh::elements_after)
      .def_readonly("force_before", &Remesh::force_before, "N, on the old mesh")
      .def_readonly("force_after", &Remesh::force_after, "N, on the new mesh at the same depth")
      .def_property_readonly("force_jump", &Remesh::force_jump, "force_after / force_before - 1")
      .def_readonly("min_volume_ratio_before", &Remesh::min_volume_ratio_before)
      .def_readonly("min_volume_ratio_after", &Remesh::min_volume_ratio_after)
      .def_readonly("seconds", &Remesh::seconds, "s")
      .def_readonly("balance", &Remesh::balance, "how the new mesh came to equilibrium (when the rezoning worked)");
  py::class_<IndentationResult>(m, "IndentationResult",
                                "Every converged step; depth, force, ... as numpy arrays (one entry per step).")
      .def_readonly("status", &IndentationResult::status)
      .def_readonly("reason", &IndentationResult::reason)
      .def_readonly("steps", &IndentationResult::steps)
      .def_readonly("puncture", &IndentationResult::puncture)
      .def_readonly("needles", &IndentationResult::needles, "one NeedleOutcome per needle (of the whole array)")
      .def_readonly("array", &IndentationResult::array, "an ArrayOutcome for an array case, else None")
      .def_readonly("bending", &IndentationResult::bending, "BendingCheck or None (no material with allowable_stress)")
      .def_readonly("remeshes", &IndentationResult::remeshes, "the rezonings, in order")
      .def_readonly("elements", &IndentationResult::elements)
      .def_readonly("nodes", &IndentationResult::nodes)
      .def_readonly("dofs", &IndentationResult::dofs)
      .def_readonly("quality", &IndentationResult::quality)
      .def_readonly("mesh_seconds", &IndentationResult::mesh_seconds, "s")
      .def_readonly("setup_seconds", &IndentationResult::setup_seconds, "s")
      .def_readonly("total_seconds", &IndentationResult::total_seconds, "s")
      .def_property_readonly(
          "depth", [](const IndentationResult& r) { return step_column<double>(r, &IndentationStep::depth); }, "m")
      .def_property_readonly(
          "force", [](const IndentationResult& r) { return step_column<double>(r, &IndentationStep::force); }, "N")
      .def_property_readonly(
          "contact_pressure",
          [](const IndentationResult& r) { return step_column<double>(r, &IndentationStep::contact_pressure); }, "Pa")
      .def_property_readonly(
          "averaged_pressure",
          [](const IndentationResult& r) { return step_column<double>(r, &IndentationStep::averaged_pressure); }, "Pa")
      .def_property_readonly(
          "strain_energy",
          [](const IndentationResult& r) { return step_column<double>(r, &IndentationStep::strain_energy); }, "J")
      .def_property_readonly(
          "min_volume_ratio",
          [](const IndentationResult& r) { return step_column<double>(r, &IndentationStep::min_volume_ratio); },
          "the most compressed tetrahedron's J = det F per step (below 0.3: forces depend on the mesh)")
      .def_property_readonly(
          "tip_embedded_depth",
          [](const IndentationResult& r) { return step_column<double>(r, &IndentationStep::tip_embedded_depth); },
          "m per step, how far the needles' tips lie inside the tissue past its top surface (surface contact)");
  m.def(
      "run_indentation",
      [](const IndentationCase& c, py::object progress, std::optional<std::string> output_directory) {
        ProgressRelay relay(std::move(progress));
        IndentationOptions options;
        // The run has no "stop" answer: a Ctrl-C (or an exception of the callback) unwinds it from here.
        options.progress = [&relay](const IndentationProgress& p) {
          if (!relay.keep_going(p)) throw RunStopped{};
        };
        std::optional<io::IndentationWriter> writer;
        if (output_directory) {
          writer.emplace(*output_directory, c);
          options.on_mesh = [&writer](const mesh::TetMesh& tissue) { writer->set_mesh(tissue); };
          options.on_step = [&writer](const IndentationStep& s, const fem::QuasiStaticSolver& solver) {
            writer->write_step(s, solver);
          };
          options.on_remesh = [&writer](const Remesh& remesh) { writer->add_remesh(remesh); };
        }
        IndentationResult result;
        try {
          py::gil_scoped_release released;
          result = run_indentation(c, options);
          if (writer) writer->finish(result);
        } catch (const RunStopped&) {
        }
        relay.rethrow();
        return result;
      },
      py::arg("case"), py::arg("progress") = py::none(), py::arg("output_directory") = py::none(),
      "Runs the FE indentation (GIL released). progress(IndentationProgress) is called at each stage and Newton "
      "iteration; Ctrl-C raises KeyboardInterrupt (files of completed steps are complete, none is half-written). "
      "output_directory: the ParaView series (NAME.pvd, NAME_step_KKK.vtu), CSV and JSON as `needlekit indent --out`.");
  m.def("set_array", &set_array, py::arg("case"), py::arg("array"), py::arg("tip_height") = 0.0,
        py::arg("size_width") = true, py::arg("size_length") = true,
        "Makes the case an array case: every needle of `array` at tip_height (m), and the block's width and length "
        "the array's footprint plus its margin (when size_width / size_length).");
  m.def("pre_puncture_curve", &pre_puncture_curve, py::arg("result"));
  m.def(
      "indentation_json",
      [](const IndentationCase& c, const IndentationResult& r) { return to_python(io::indentation_json(c, r)); },
      py::arg("case"), py::arg("result"), "The result JSON of `needlekit indent` (units in the keys).");
  m.def("force_depth_csv", &io::force_depth_csv, py::arg("result"));
}

void bind_post_puncture(py::module_& m) {
  py::class_<TriangleClassificationOptions> classification(
      m, "TriangleClassificationOptions", "The triangle classes of §3.6.1 (side, back, channel, alpha, beta).");
  classification
      .def_readwrite("insertion_direction", &TriangleClassificationOptions::insertion_direction,
                     "d, any length > 0 (normalised inside); default +z, the needle frame's tip direction")
      .def_readwrite("axis_point", &TriangleClassificationOptions::axis_point,
                     "m, a point on the needle's centre axis (parallel to d); default the origin");
  def_parameters<TriangleClassificationOptions>(classification, kTriangleClassificationParameters);  // keyword init
  py::class_<PostPunctureOptions> post_puncture(m, "PostPunctureOptions",
                                                "The beta load of the post-puncture force (§3.6.2, Algorithm 3.1).");
  post_puncture.def_readwrite("axis_point", &PostPunctureOptions::axis_point,
                              "m, a point on the channel axis (NaN: the centroid of the tip vertices)");
  def_parameters<PostPunctureOptions>(post_puncture, kPostPunctureParameters);  // every other field; keyword init
  py::class_<PostPunctureLoads>(m, "PostPunctureLoads", "The loaded triangles of a needle (§3.6).")
      .def_readonly("reference_radius", &PostPunctureLoads::reference_radius, "m")
      .def_readonly("needle_length", &PostPunctureLoads::needle_length, "m")
      .def_readonly("alpha_area", &PostPunctureLoads::alpha_area, "m^2");
  m.def(
      "post_puncture_loads",
      [](const geometry::TriangleMesh& needle, const TriangleClassificationOptions& c, const PostPunctureOptions& o) {
        return post_puncture_loads(needle, c, o);
      },
      py::arg("needle"), py::arg("classification") = TriangleClassificationOptions{},
      py::arg("options") = PostPunctureOptions{});
  m.def(
      "post_puncture_forces",
      [](const PostPunctureLoads& loads, py::handle depths, py::handle stiffness, double scale) {
        return owning_array(post_puncture_forces(loads, values_from(depths, "inserted_depths"),
                                                 quantity(stiffness, Dimension::Pressure, "stiffness"), scale));
      },
      py::arg("loads"), py::arg("inserted_depths"), py::arg("stiffness"), py::arg("scale"),
      "Post-puncture force (N) at inserted depths (m); stiffness K in N/m^2 (\"0.84 N/mm2\"), scale S (Eq 3.18).");

  bind_enum<kInsertionPhaseNames>(m, "InsertionPhase", "The phase of a point of an insertion curve.");
  bind_enum<kInsertionStatusNames>(m, "InsertionStatus", "The outcome of insertion_curve.");
  py::class_<PunctureEvent>(m, "PunctureEvent")
      .def_readonly("needle", &PunctureEvent::needle)
      .def_readonly("displacement", &PunctureEvent::displacement, "m")
      .def_readonly("depth", &PunctureEvent::depth, "m")
      .def_readonly("force_before", &PunctureEvent::force_before, "N")
      .def_readonly("force_after", &PunctureEvent::force_after, "N")
      .def_readonly("drop", &PunctureEvent::drop, "N");
  py::class_<InsertionCurve>(m, "InsertionCurve", "The complete insertion curve (§3.5-3.6); depth (m), force (N).")
      .def_readonly("status", &InsertionCurve::status)
      .def_readonly("reason", &InsertionCurve::reason)
      .def_property_readonly(
          "depth", [](py::object self) { return values_view(self.cast<const InsertionCurve&>().depth, self); }, "m")
      .def_property_readonly(
          "force", [](py::object self) { return values_view(self.cast<const InsertionCurve&>().force, self); }, "N")
      .def_readonly("phase", &InsertionCurve::phase)
      .def_readonly("punctured_needles", &InsertionCurve::punctured_needles)
      .def_readonly("punctures", &InsertionCurve::punctures)
      .def_readonly("needle_force", &InsertionCurve::needle_force,
                    "N, per needle, per sample: its indentation force until it punctures, its cutting force after");
  m.def(
      "insertion_curve",
      [](const std::vector<PrePunctureCurve>& pre, const PostPunctureLoads& loads, py::handle stiffness, double scale,
         std::vector<double> contact_offsets, py::handle final_depth, int cutting_samples) {
        std::vector<NeedleInsertion> needles(pre.size());
        for (std::size_t i = 0; i < pre.size(); ++i) {
          needles[i].pre_puncture = pre[i];
          needles[i].loads = &loads;
          needles[i].stiffness = quantity(stiffness, Dimension::Pressure, "stiffness");
          needles[i].scale = scale;
          needles[i].contact_offset = i < contact_offsets.size() ? contact_offsets[i] : 0.0;
        }
        InsertionCurveOptions options;
        options.final_depth = quantity(final_depth, Dimension::Length, "final_depth");
        options.cutting_samples = cutting_samples;
        return insertion_curve(needles, options);
      },
      py::arg("pre_puncture"), py::arg("loads"), py::arg("stiffness"), py::arg("scale"),
      py::arg("contact_offsets") = std::vector<double>{}, py::arg("final_depth") = 1e-3,
      py::arg("cutting_samples") = 200,
      "The complete insertion curve of needles sharing one post-puncture load (one PrePunctureCurve per needle).");
  m.def(
      "insertion_curve_json", [](const InsertionCurve& c) { return to_python(io::insertion_curve_json(c)); },
      py::arg("curve"));
  m.def("insertion_curve_csv", &io::insertion_curve_csv, py::arg("curve"));
}

void bind_complete_insertion(py::module_& m) {
  py::class_<PostPunctureFitOptions> model(m, "PostPunctureFitOptions", "K and S of Eq 3.18, and which one to fit.");
  def_parameters<PostPunctureFitOptions>(model, kPostPunctureFitParameters);  // every field; keyword init
  py::class_<PostPunctureFit>(m, "PostPunctureFit")
      .def_readonly("stiffness", &PostPunctureFit::stiffness, "N/m^2")
      .def_readonly("scale", &PostPunctureFit::scale)
      .def_readonly("rms_error", &PostPunctureFit::rms_error, "N");
  py::class_<InsertionCurveOptions> curve(m, "InsertionCurveOptions", "The complete curve's end and samples.");
  def_parameters<InsertionCurveOptions>(curve, kInsertionCurveParameters);  // every field; keyword init
  py::class_<CompleteInsertionOptions> options(
      m, "CompleteInsertionOptions",
      "The post-puncture model, an optional measured curve to fit, the curve's "
      "final depth, or a given pre-puncture curve (no FE).");
  def_keyword_init<CompleteInsertionOptions>(options);
  options.def_readwrite("model", &CompleteInsertionOptions::model)
      .def_readwrite("measured", &CompleteInsertionOptions::measured)
      .def_readwrite("post_puncture", &CompleteInsertionOptions::post_puncture)
      .def_readwrite("classification", &CompleteInsertionOptions::classification)
      .def_readwrite("curve", &CompleteInsertionOptions::curve)
      .def_readwrite("pre_puncture", &CompleteInsertionOptions::pre_puncture);
  bind_enum<kCompleteInsertionStatusNames>(m, "CompleteInsertionStatus", "The outcome of a complete insertion.");
  py::class_<CompleteInsertionResult>(m, "CompleteInsertionResult")
      .def_readonly("status", &CompleteInsertionResult::status)
      .def_readonly("reason", &CompleteInsertionResult::reason)
      .def_readonly("indentation", &CompleteInsertionResult::indentation)
      .def_readonly("loads", &CompleteInsertionResult::loads)
      .def_readonly("fit", &CompleteInsertionResult::fit)
      .def_readonly("stiffness", &CompleteInsertionResult::stiffness, "N/m^2, K used")
      .def_readonly("scale", &CompleteInsertionResult::scale, "S used")
      .def_readonly("curve", &CompleteInsertionResult::curve);
  m.def(
      "complete_insertion",
      [](const IndentationCase& c, CompleteInsertionOptions options, py::object progress) {
        ProgressRelay relay(std::move(progress));
        options.indentation.progress = [&relay](const IndentationProgress& p) {
          if (!relay.keep_going(p)) throw RunStopped{};
        };
        CompleteInsertionResult result;
        try {
          py::gil_scoped_release released;
          result = complete_insertion(c, options);
        } catch (const RunStopped&) {
        }
        relay.rethrow();
        return result;
      },
      py::arg("case"), py::arg("options") = CompleteInsertionOptions{}, py::arg("progress") = py::none(),
      "The complete insertion (§3.4-3.6): post-puncture load, FE indentation to puncture, the force curve to the final "
      "depth; what `needlekit insert` runs. GIL released; progress(IndentationProgress); Ctrl-C: KeyboardInterrupt.");
  py::class_<io::InsertionCase>(m, "InsertionCase", "An insertion case file (`needlekit insert CASE.toml`).")
      .def_readwrite("indentation", &io::InsertionCase::indentation)
      .def_readwrite("options", &io::InsertionCase::options)
      .def_readwrite("measured", &io::InsertionCase::measured);
  m.def("read_insertion_case", &io::read_insertion_case, py::arg("path"),
        "Reads an insertion case file; raises InvalidInput / IoError naming file, line and key.");
}

}  // namespace

void bind_insertion(py::module_& m) {
  bind_indentation(m);
  bind_post_puncture(m);
  bind_complete_insertion(m);
}

}  // namespace needlekit::python
