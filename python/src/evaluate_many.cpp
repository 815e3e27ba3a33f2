// needlekit.evaluate_many: arrays of designs in, arrays of every quantity out (analysis/evaluate_many.hpp). Columns
// are taken from numpy without a copy when they are float64 (int64 for needles_per_row) and contiguous; the outputs
// are numpy arrays that own the library's vectors.
#include "needlekit/analysis/evaluate_many.hpp"

#include <fmt/format.h>

#include "common.hpp"
#include "needlekit/analysis/puncture_model.hpp"
#include "needlekit/materials/needle_material.hpp"

namespace needlekit::python {
namespace {

using analysis::DesignColumns;

// Keeps the converted numpy columns alive while the library reads them.
struct ColumnStore {
  std::vector<py::object> arrays;
  std::vector<std::vector<double>> scalars;

  template <class T>
  py::array_t<T, py::array::c_style> numeric(py::handle value, std::string_view name) {
    py::array array;
    try {
      array = py::array::ensure(value);
    } catch (const py::error_already_set&) {
    }
    if (!array || (array.dtype().kind() != 'f' && array.dtype().kind() != 'i' && array.dtype().kind() != 'u' &&
                   array.dtype().kind() != 'b')) {
      throw_invalid(fmt::format("{}: expected a number, a string with a unit or a 1-D array of numbers, got {}", name,
                                std::string(py::str(array ? py::object(array.dtype()) : py::type::of(value)))));
    }
    if (array.ndim() > 1) throw_invalid(fmt::format("{}: expected a 1-D array, got {} dimensions", name, array.ndim()));
    auto typed = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!typed) throw_invalid(fmt::format("{}: cannot be converted to numbers", name));
    if constexpr (std::is_integral_v<T>) {
      if (array.dtype().kind() != 'f') {
        arrays.push_back(typed);
        return typed;
      }
      auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
      for (py::ssize_t i = 0; i < doubles.size(); ++i) {
        if (doubles.data()[i] != static_cast<double>(typed.data()[i])) {
          throw_invalid(fmt::format("{}[{}]: {} is not a whole number", name, i, doubles.data()[i]));
        }
      }
    }
    arrays.push_back(typed);
    return typed;
  }

  std::span<const double> quantities(py::handle value, Dimension dimension, std::string_view name) {
    if (py::isinstance<py::str>(value)) {
      scalars.push_back({quantity(value, dimension, name)});
      return scalars.back();
    }
    const auto array = numeric<double>(value, name);
    return {array.data(), static_cast<std::size_t>(array.size())};
  }
};

}  // namespace

void bind_evaluate_many(py::module_& m) {
  m.def(
      "_evaluate_many",
      [](py::handle shape, py::handle needles_per_row, py::handle tip_diameter, py::handle base_diameter,
         py::handle bore_diameter, py::handle length, py::handle width, py::handle angle, py::handle target_depth,
         py::handle material, py::handle tissue, const analysis::PerformanceIndexOptions& options) {
        ColumnStore store;
        store.scalars.reserve(16);
        DesignColumns columns;
        // Shapes: names, Shape values or codes 0/1/2.
        std::vector<std::uint8_t> shape_codes;
        const auto shape_code = [](py::handle item, std::size_t i) {
          if (py::isinstance<py::str>(item)) {
            return static_cast<std::uint8_t>(
                needle::shape_from_string(item.cast<std::string>(), fmt::format("shape[{}]", i)));
          }
          if (py::isinstance<needle::Shape>(item)) return static_cast<std::uint8_t>(item.cast<needle::Shape>());
          const auto code = item.cast<long long>();
          if (code < 0 || code > 2) throw_invalid(fmt::format("shape[{}]: {} is not a shape code (0, 1, 2)", i, code));
          return static_cast<std::uint8_t>(code);
        };
        if (py::isinstance<py::str>(shape) || py::isinstance<needle::Shape>(shape)) {
          shape_codes.push_back(shape_code(shape, 0));
        } else if (py::isinstance<py::array>(shape) &&
                   (py::reinterpret_borrow<py::array>(shape).dtype().kind() == 'i' ||
                    py::reinterpret_borrow<py::array>(shape).dtype().kind() == 'u')) {
          const auto codes = store.numeric<std::int64_t>(shape, "shape");  // codes, checked by the library
          for (py::ssize_t i = 0; i < codes.size(); ++i) {
            if (codes.data()[i] < 0 || codes.data()[i] > 2) shape_code(py::int_(codes.data()[i]), i);
            shape_codes.push_back(static_cast<std::uint8_t>(codes.data()[i]));
          }
        } else {
          for (std::size_t i = 0; const py::handle item : py::iter(shape)) shape_codes.push_back(shape_code(item, i++));
        }
        columns.shape = shape_codes;
        const auto n = store.numeric<std::int64_t>(needles_per_row, "needles_per_row");
        columns.needles_per_row = {n.data(), static_cast<std::size_t>(n.size())};
        columns.tip_diameter = store.quantities(tip_diameter, Dimension::Length, "tip_diameter");
        columns.base_diameter = store.quantities(base_diameter, Dimension::Length, "base_diameter");
        columns.bore_diameter = store.quantities(bore_diameter, Dimension::Length, "bore_diameter");
        columns.length = store.quantities(length, Dimension::Length, "length");
        columns.width = store.quantities(width, Dimension::Length, "width");
        columns.angle = store.quantities(angle, Dimension::Angle, "angle");
        columns.target_depth = store.quantities(target_depth, Dimension::Length, "target_depth");
        analysis::SharedInputs shared;
        shared.material = py::isinstance<py::str>(material) ? materials::material_preset(material.cast<std::string>())
                                                            : material.cast<materials::NeedleMaterial>();
        shared.tissue = py::isinstance<py::str>(tissue)
                            ? analysis::puncture_model_preset(tissue.cast<std::string>(), "tissue")
                            : tissue.cast<analysis::PunctureModel>();
        shared.options = options;
        analysis::ManyResults results;
        {
          py::gil_scoped_release released;
          results = analysis::evaluate_many(columns, shared);
        }
        py::dict out;
        const auto names = analysis::result_columns();
        for (std::size_t c = 0; c < names.size(); ++c) {
          out[py::str(std::string(names[c].name))] = owning_array(std::move(results.values[c]));
        }
        out["status"] = owning_array(std::move(results.status));
        out["failed_checks"] = owning_array(std::move(results.failed_checks));
        out["buckling_method"] = owning_array(std::move(results.buckling_method));
        out["bending_ok"] = owning_array(std::move(results.bending_ok));
        out["small_tip_branch"] = owning_array(std::move(results.small_tip_branch));
        out["distinct_sections"] = results.distinct_sections;
        return out;
      },
      py::arg("shape"), py::arg("needles_per_row"), py::arg("tip_diameter"), py::arg("base_diameter"),
      py::arg("bore_diameter"), py::arg("length"), py::arg("width"), py::arg("angle"), py::arg("target_depth"),
      py::arg("material"), py::arg("tissue"), py::arg("options"),
      "The compiled part of needlekit.evaluate_many (which documents the arguments).");
  py::list columns;
  for (const analysis::ResultColumn& c : analysis::result_columns()) {
    columns.append(py::make_tuple(std::string(c.name), std::string(c.unit)));
  }
  m.attr("evaluate_many_columns") = py::tuple(columns);
}

}  // namespace needlekit::python
