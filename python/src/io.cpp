// needlekit/io: design and design-space files (`evaluate`, `sweep`, `optimize`) and the atomic text writer.
#include "common.hpp"
#include "needlekit/io/design_config.hpp"
#include "needlekit/io/result_writers.hpp"

namespace needlekit::python {

void bind_io(py::module_& m) {
  py::class_<io::DesignFile>(m, "DesignFile", "A design file: the array, the insertion conditions and the options.")
      .def_readwrite("design", &io::DesignFile::design)
      .def_readwrite("conditions", &io::DesignFile::conditions)
      .def_readwrite("options", &io::DesignFile::options);
  m.def("read_design_file", &io::read_design_file, py::arg("path"),
        "Reads a design file (TOML); raises InvalidInput / IoError naming file, line and key.");
  m.def("parse_design_toml", &io::parse_design_toml, py::arg("text"), py::arg("source_name") = "<text>");
  py::class_<io::SpaceFile>(m, "SpaceFile")
      .def_readwrite("space", &io::SpaceFile::space)
      .def_readwrite("robust", &io::SpaceFile::robust, "RobustSpec when min_success_probability is given, else None");
  m.def("read_space_file", &io::read_space_file, py::arg("path"), "Reads a design-space file (`needlekit optimize`).");
  m.def("parse_space_toml", &io::parse_space_toml, py::arg("text"), py::arg("source_name") = "<text>");
  m.def("write_text_file_atomically", &io::write_text_file_atomically, py::arg("path"), py::arg("content"),
        "Writes to a temporary name and renames: no half-written file.");
}

}  // namespace needlekit::python
