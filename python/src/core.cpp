// needlekit/core: units (parse and format quantities) and the exit codes.
#include "common.hpp"
#include "enum_binding.hpp"
#include "needlekit/core/exit_codes.hpp"

namespace needlekit::python {

void bind_core(py::module_& m) {
  bind_enum<units::kDimensionNames>(m, "Dimension", "The physical dimension of a quantity (its SI unit: si_symbol()).");
  m.def(
      "si_symbol", [](Dimension d) { return std::string(units::si_symbol(d)); }, py::arg("dimension"),
      "The SI unit symbol of a dimension (\"m\", \"Pa\", ...).");
  m.def(
      "dimension_name", [](Dimension d) { return std::string(units::dimension_name(d)); }, py::arg("dimension"));
  m.def("parse_quantity", &units::parse_quantity, py::arg("text"), py::arg("expected"), py::arg("what") = "value",
        "\"<number> <unit>\" in SI, e.g. parse_quantity(\"230 um\", Dimension.Length) == 2.3e-4. Raises InvalidInput "
        "naming `what` for a unit of another dimension.");
  m.def("unit_factor", &units::unit_factor, py::arg("unit"), py::arg("expected"), py::arg("what") = "unit",
        "The factor that converts a value in `unit` to SI.");
  m.def("format", &units::format, py::arg("value_si"), py::arg("unit"), py::arg("significant_digits") = 6,
        "An SI value in the given unit, e.g. format(2.3e-4, \"um\") == \"230 um\".");
  bind_enum<kExitCodeNames, 256>(m, "ExitCode", "The needlekit tool's exit codes.");
}

}  // namespace needlekit::python
