// The needlekit Python module (the compiled part, needlekit._needlekit; needlekit/__init__.py re-exports it). Names
// are those of the C++ API; every domain binds itself in its own file.
#include "common.hpp"
#include "needlekit/core/errors.hpp"

PYBIND11_MODULE(_needlekit, m) {
  namespace nk = needlekit::python;
  m.doc() =
      "needlekit: microneedle design and analysis (P. Boonma 2012). SI units inside; every quantity may also be "
      "given as a string with its unit (\"230 um\").";
  pybind11::register_exception<needlekit::InvalidInput>(m, "InvalidInput", PyExc_ValueError);
  pybind11::register_exception<needlekit::IoError>(m, "IoError", PyExc_OSError);
  // In dependency order: a type is registered before the signatures that name it.
  nk::bind_core(m);
  nk::bind_geometry(m);
  nk::bind_needle(m);
  nk::bind_analysis(m);
  nk::bind_evaluate_many(m);
  nk::bind_mesh(m);
  nk::bind_needle_array(m);
  nk::bind_insertion(m);
  nk::bind_patch(m);
  nk::bind_calibration(m);
  nk::bind_uncertainty(m);
  nk::bind_uncertainty_patch_and_fe(m);
  nk::bind_io(m);
}
