// needlekit/insertion: microneedle arrays (issue 36) — the `[array]` of an indentation case, and the per-needle and
// whole-array results of a run (IndentationResult.needles, .array).
#include "common.hpp"
#include "enum_binding.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/needle_array.hpp"

namespace needlekit::python {

void bind_needle_array(py::module_& m) {
  using namespace insertion;
  bind_enum<kArrayLayoutNames>(m, "ArrayLayout", "How the needles of an array are placed ([array] layout).");
  bind_enum<kArraySymmetryNames>(m, "ArraySymmetry", "The reduced model an array's symmetry allows ([array] symmetry).");

  py::class_<NeedleArray> array(m, "NeedleArray",
                                "A needle array: the case's needle repeated on a grid, all needles moving together "
                                "(docs/arrays.md). Needle k = row * columns + column, centred on the block.");
  def_keyword_init<NeedleArray>(array);
  array.def_readwrite("layout", &NeedleArray::layout)
      .def_readwrite("rows", &NeedleArray::rows, "[1, 100]: needles along y")
      .def_readwrite("columns", &NeedleArray::columns, "[1, 100]: needles along x")
      .def_readwrite("backing_plate", &NeedleArray::backing_plate, "a rigid plate at the needles' base (the patch)")
      .def_readwrite("symmetry", &NeedleArray::symmetry);
  def_quantity(array, "pitch", &NeedleArray::pitch, Dimension::Length,
               "m, > 0: centre distance of neighbouring needles, at least the needle's base diameter");
  def_quantity(array, "margin", &NeedleArray::margin, Dimension::Length,
               "m, >= 0: tissue beyond the footprint on every side when the block's size is not given");
  m.def("array_positions", &array_positions, py::arg("array"), "m: the (x, y) of every needle's tip centre.");
}

void bind_needle_outcomes(py::module_& m) {
  using namespace insertion;
  py::class_<NeedleOutcome>(m, "NeedleOutcome", "One needle of an indentation run (of the whole array), per step.")
      .def_readonly("position", &NeedleOutcome::position, "m, (x, y) of the tip's centre")
      .def_property_readonly(
          "force", [](const NeedleOutcome& n) { return owning_array(std::vector<double>(n.force)); }, "N, per step")
      .def_property_readonly(
          "depth", [](const NeedleOutcome& n) { return owning_array(std::vector<double>(n.depth)); },
          "m, per step: the tip below the undeformed surface")
      .def_readonly("puncture", &NeedleOutcome::puncture, "its own puncture point, None if it did not puncture")
      .def_readonly("puncture_step", &NeedleOutcome::puncture_step, "the step (from 1) it punctured in; 0: not")
      .def_readonly("inserted_depth", &NeedleOutcome::inserted_depth,
                    "m: travel beyond its puncture depth at the last step (0 when not punctured)");
  py::class_<ArrayOutcome>(m, "ArrayOutcome", "The totals of an array run (Larrañeta et al. 2014's penetrated fraction).")
      .def_property_readonly(
          "plate_travel", [](const ArrayOutcome& a) { return owning_array(std::vector<double>(a.plate_travel)); },
          "m, per step: the needles' (and the plate's) common displacement")
      .def_property_readonly(
          "punctured_fraction",
          [](const ArrayOutcome& a) { return owning_array(std::vector<double>(a.punctured_fraction)); },
          "[0, 1], per step: the needles punctured so far")
      .def_readonly("first_puncture_travel", &ArrayOutcome::first_puncture_travel,
                    "m: the plate's travel when the first needle punctured, None if none did")
      .def_readonly("mean_inserted_depth", &ArrayOutcome::mean_inserted_depth, "m, over every needle, last step")
      .def_readonly("inserted_depth_spread", &ArrayOutcome::inserted_depth_spread, "m, standard deviation")
      .def_readonly("mean_penetrated_fraction", &ArrayOutcome::mean_penetrated_fraction,
                    "[0, 1]: mean inserted depth / the needle's length");
}

}  // namespace needlekit::python
