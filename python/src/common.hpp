// What every binding file of the needlekit Python module shares: quantities from Python (SI floats or strings with
// units, parsed by needlekit::units), numpy arrays in and out (views without copies where the layout allows), JSON
// to Python objects, and runs that release the GIL and stop on Ctrl-C. Presentation only: no needlekit logic here.
#pragma once
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <Eigen/Core>
#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "needlekit/core/units.hpp"

namespace needlekit::python {

namespace py = pybind11;
using units::Dimension;

// The binding of one domain each (one source file per domain).
void bind_core(py::module_& m);
void bind_needle(py::module_& m);
void bind_analysis(py::module_& m);
void bind_evaluate_many(py::module_& m);
void bind_geometry(py::module_& m);
void bind_mesh(py::module_& m);
void bind_needle_array(py::module_& m);
void bind_needle_outcomes(py::module_& m);  // after PuncturePoint, before IndentationResult (bind_insertion)
void bind_insertion(py::module_& m);
void bind_patch(py::module_& m);
void bind_calibration(py::module_& m);
void bind_uncertainty(py::module_& m);
void bind_uncertainty_patch_and_fe(py::module_& m);
void bind_io(py::module_& m);

// Throws needlekit::InvalidInput (needlekit.InvalidInput in Python, a ValueError).
[[noreturn]] void throw_invalid(const std::string& message);

// A quantity: a float or int is taken as SI, a string is parsed with its unit ("230 um"). Throws InvalidInput
// naming `what` for another type, a string of the wrong dimension, or a non-finite value.
double quantity(py::handle value, Dimension dimension, std::string_view what);

// A property in SI that accepts a quantity (SI float or string with unit) when set.
template <class Class, class Owner>
void def_quantity(Class& cls, const char* name, double Owner::*member, Dimension dimension, const char* doc) {
  cls.def_property(
      name, [member](const Owner& owner) { return owner.*member; },
      [member, dimension, name](Owner& owner, py::handle value) { owner.*member = quantity(value, dimension, name); },
      doc);
}
// The same for an optional quantity (None: not given).
template <class Class, class Owner>
void def_optional_quantity(Class& cls, const char* name, std::optional<double> Owner::*member, Dimension dimension,
                           const char* doc) {
  cls.def_property(
      name, [member](const Owner& owner) { return owner.*member; },
      [member, dimension, name](Owner& owner, py::handle value) {
        if (value.is_none()) {
          owner.*member = std::nullopt;
        } else {
          owner.*member = quantity(value, dimension, name);
        }
      },
      doc);
}

// A keyword constructor T(field=value, ...) that sets the named properties (an unknown name is InvalidInput).
template <class T, class Class>
void def_keyword_init(Class& cls) {
  cls.def(py::init([](const py::kwargs& fields) {
            py::object object = py::cast(T{});
            const py::object type = py::type::of(object);
            const py::object property = py::module_::import("builtins").attr("property");
            for (const auto& [key, value] : fields) {
              const std::string name = py::str(key);
              if (!py::hasattr(type, name.c_str()) || !py::isinstance(type.attr(name.c_str()), property)) {
                throw_invalid(std::string(py::str(type.attr("__name__"))) + ": no field '" + name + "'");
              }
              object.attr(name.c_str()) = value;
            }
            return object.cast<T>();
          }),
          "Keyword constructor: every field can be given by name; quantities as SI floats or strings with units.");
}
// Read-only numpy views of library arrays, kept alive by `owner` (the Python object that holds the vector).
py::array_t<double> points_view(const std::vector<Eigen::Vector3d>& points, py::handle owner);
py::array_t<double> points_view(const std::vector<Eigen::Vector2d>& points, py::handle owner);
py::array_t<double> values_view(const std::vector<double>& values, py::handle owner);
py::array_t<int> index_view(const std::vector<std::array<int, 3>>& rows, py::handle owner);
py::array_t<int> index_view(const std::vector<std::array<int, 4>>& rows, py::handle owner);
py::array_t<int> values_view(const std::vector<int>& values, py::handle owner);

// A numpy array that owns the vector (no copy).
template <class T>
py::array_t<T> owning_array(std::vector<T>&& values) {
  auto* held = new std::vector<T>(std::move(values));
  py::capsule free_when_done(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(held->size())}, {static_cast<py::ssize_t>(sizeof(T))}, held->data(),
                        free_when_done);
}

// Arrays from Python. Throw InvalidInput naming `what` (and the index) for a wrong type, shape, or a non-finite value.
std::vector<Eigen::Vector3d> points_from(py::handle value, std::string_view what);
std::vector<Eigen::Vector2d> points2_from(py::handle value, std::string_view what);
std::vector<double> values_from(py::handle value, std::string_view what);
template <std::size_t N>
std::vector<std::array<int, N>> index_rows_from(py::handle value, std::string_view what);

// JSON as Python dicts, lists, floats, ints, strings, bools and None, numbers as the CLI writes them (floats rounded
// to 12 significant digits, io/json_text.hpp).
py::object to_python(const nlohmann::json& json);

// Calls the user's progress callback (optional) and checks for Ctrl-C, from library progress callbacks running with
// the GIL released. Once a Python exception is raised there (KeyboardInterrupt from Ctrl-C, or the callback's own),
// keep_going() returns false and rethrow() raises it after the run.
class ProgressRelay {
 public:
  explicit ProgressRelay(py::object callback) : callback_(std::move(callback)) {}
  template <class... Args>
  bool keep_going(Args&&... args) {
    py::gil_scoped_acquire gil;
    if (stopped_) return false;
    try {
      if (callback_ && !callback_.is_none()) callback_(std::forward<Args>(args)...);
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } catch (py::error_already_set& error) {
      error_ = std::move(error);
      stopped_ = true;
    }
    return !stopped_;
  }
  bool stopped() const { return stopped_; }
  void rethrow() {
    if (stopped_) throw std::move(*error_);
  }

 private:
  py::object callback_;
  bool stopped_ = false;
  std::optional<py::error_already_set> error_;
};

// Thrown through the library by a progress callback that cannot return "stop" (run_indentation): unwinds the run.
struct RunStopped {};

}  // namespace needlekit::python
