#include "common.hpp"

#include <fmt/format.h>

#include <cmath>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"

namespace needlekit::python {

void throw_invalid(const std::string& message) { throw InvalidInput(message); }

double quantity(py::handle value, Dimension dimension, std::string_view what) {
  double si = 0;
  if (py::isinstance<py::str>(value)) {
    si = units::parse_quantity(value.cast<std::string>(), dimension, what);
  } else if (py::isinstance<py::bool_>(value) ||
             !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
               py::hasattr(value, "__float__"))) {
    throw InvalidInput(
        fmt::format("{}: {} is not a quantity, expected a number in {} or a string with a unit of {} "
                    "(e.g. \"230 um\")",
                    what, std::string(py::str(py::type::of(value).attr("__name__"))), units::si_symbol(dimension),
                    units::dimension_name(dimension)));
  } else {
    si = value.cast<double>();
  }
  if (!std::isfinite(si)) throw InvalidInput(fmt::format("{}: {} is not a finite number", what, si));
  return si;
}

namespace {

template <class T>
py::array_t<T> read_only(py::array_t<T> array) {
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

template <class Row, class T, std::size_t N>
py::array_t<T> rows_view(const std::vector<Row>& rows, py::handle owner) {
  static_assert(sizeof(Row) == N * sizeof(T), "rows must be packed");
  const T* data = rows.empty() ? nullptr : reinterpret_cast<const T*>(rows.data());
  return read_only(py::array_t<T>({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)},
                                  {static_cast<py::ssize_t>(sizeof(Row)), static_cast<py::ssize_t>(sizeof(T))}, data,
                                  owner));
}

// A numeric numpy array of `ndim` dimensions (the last of size `columns` when > 0), as float64, C order.
py::array_t<double, py::array::c_style> numeric_array(py::handle value, std::string_view what, int ndim,
                                                      py::ssize_t columns) {
  py::array array;
  try {
    array = py::array::ensure(value);
  } catch (const py::error_already_set&) {
  }
  const std::string expected = columns > 0 ? fmt::format("an array of shape (N, {})", columns) : "a 1-D array";
  if (!array || py::isinstance<py::str>(value)) {
    throw InvalidInput(fmt::format("{}: {} is not {} of numbers", what,
                                   std::string(py::str(py::type::of(value).attr("__name__"))), expected));
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw InvalidInput(fmt::format("{}: an array of dtype {} is not {} of numbers", what,
                                   std::string(py::str(array.dtype())), expected));
  }
  if (array.ndim() != ndim || (columns > 0 && array.shape(ndim - 1) != columns)) {
    std::vector<std::string> shape;
    for (py::ssize_t d = 0; d < array.ndim(); ++d) shape.push_back(std::to_string(array.shape(d)));
    throw InvalidInput(fmt::format("{}: an array of shape ({}) is not {}", what, fmt::join(shape, ", "), expected));
  }
  auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  const double* data = doubles.data();
  const py::ssize_t width = columns > 0 ? columns : 1;
  for (py::ssize_t i = 0; i < doubles.size(); ++i) {
    if (!std::isfinite(data[i])) {
      throw InvalidInput(columns > 0
                             ? fmt::format("{}[{}, {}]: {} is not a finite number", what, i / width, i % width, data[i])
                             : fmt::format("{}[{}]: {} is not a finite number", what, i, data[i]));
    }
  }
  return doubles;
}

template <class Point, int N>
std::vector<Point> points_of(py::handle value, std::string_view what) {
  const auto array = numeric_array(value, what, 2, N);
  std::vector<Point> points(static_cast<std::size_t>(array.shape(0)));
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < N; ++k) points[i][k] = array.data()[i * N + k];
  return points;
}

}  // namespace

py::array_t<double> points_view(const std::vector<Eigen::Vector3d>& p, py::handle o) {
  return rows_view<Eigen::Vector3d, double, 3>(p, o);
}
py::array_t<double> points_view(const std::vector<Eigen::Vector2d>& p, py::handle o) {
  return rows_view<Eigen::Vector2d, double, 2>(p, o);
}
py::array_t<int> index_view(const std::vector<std::array<int, 3>>& r, py::handle o) {
  return rows_view<std::array<int, 3>, int, 3>(r, o);
}
py::array_t<int> index_view(const std::vector<std::array<int, 4>>& r, py::handle o) {
  return rows_view<std::array<int, 4>, int, 4>(r, o);
}
py::array_t<double> values_view(const std::vector<double>& v, py::handle o) {
  return read_only(py::array_t<double>({static_cast<py::ssize_t>(v.size())}, {sizeof(double)}, v.data(), o));
}
py::array_t<int> values_view(const std::vector<int>& v, py::handle o) {
  return read_only(py::array_t<int>({static_cast<py::ssize_t>(v.size())}, {sizeof(int)}, v.data(), o));
}

std::vector<Eigen::Vector3d> points_from(py::handle value, std::string_view what) {
  return points_of<Eigen::Vector3d, 3>(value, what);
}
std::vector<Eigen::Vector2d> points2_from(py::handle value, std::string_view what) {
  return points_of<Eigen::Vector2d, 2>(value, what);
}
std::vector<double> values_from(py::handle value, std::string_view what) {
  const auto array = numeric_array(value, what, 1, 0);
  return {array.data(), array.data() + array.size()};
}

template <std::size_t N>
std::vector<std::array<int, N>> index_rows_from(py::handle value, std::string_view what) {
  const auto array = numeric_array(value, what, 2, N);
  std::vector<std::array<int, N>> rows(static_cast<std::size_t>(array.shape(0)));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t k = 0; k < N; ++k) {
      const double index = array.data()[i * N + k];
      if (index != std::floor(index) || index < 0 || index > 2147483647.0) {
        throw InvalidInput(fmt::format("{}[{}, {}]: {} is not a node index (an integer >= 0)", what, i, k, index));
      }
      rows[i][k] = static_cast<int>(index);
    }
  }
  return rows;
}
template std::vector<std::array<int, 3>> index_rows_from<3>(py::handle, std::string_view);
template std::vector<std::array<int, 4>> index_rows_from<4>(py::handle, std::string_view);

py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(units::round_to_12_digits(j.get<double>()));  // as the CLI writes it (io/json_text.hpp)
    case nlohmann::json::value_t::string:
      return py::str(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const auto& item : j) list.append(to_python(item));
      return list;
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (const auto& [key, item] : j.items()) dict[py::str(key)] = to_python(item);
      return dict;
    }
    default:
      return py::none();
  }
}

}  // namespace needlekit::python
