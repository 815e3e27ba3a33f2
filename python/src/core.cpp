// needlekit/core: units (parse and format quantities) and the exit codes.
#include "common.hpp"
#include "needlekit/core/exit_codes.hpp"

namespace needlekit::python {

void bind_core(py::module_& m) {
  py::enum_<Dimension>(m, "Dimension", "The physical dimension of a quantity (its SI unit: si_symbol()).")
      .value("Dimensionless", Dimension::Dimensionless)
      .value("Length", Dimension::Length)
      .value("Area", Dimension::Area)
      .value("Volume", Dimension::Volume)
      .value("Force", Dimension::Force)
      .value("Pressure", Dimension::Pressure)
      .value("Energy", Dimension::Energy)
      .value("Angle", Dimension::Angle)
      .value("InverseLength", Dimension::InverseLength)
      .value("Stiffness", Dimension::Stiffness)
      .value("ForcePerArea", Dimension::ForcePerArea);
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
  py::enum_<ExitCode>(m, "ExitCode", "The needlekit tool's exit codes.")
      .value("Success", ExitCode::Success)
      .value("InternalError", ExitCode::InternalError)
      .value("InvalidInput", ExitCode::InvalidInput)
      .value("NumericalFailure", ExitCode::NumericalFailure)
      .value("Interrupted", ExitCode::Interrupted);
}

}  // namespace needlekit::python
