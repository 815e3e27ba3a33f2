#include "needlekit/io/force_curve_csv.hpp"

#include <fmt/format.h>

#include <charconv>
#include <sstream>
#include <string>
#include <vector>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "toml_config.hpp"

namespace needlekit::io {
namespace {

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) {
    while (!field.empty() && (field.back() == '\r' || field.back() == ' ')) field.pop_back();
    while (!field.empty() && field.front() == ' ') field.erase(field.begin());
    fields.push_back(field);
  }
  return fields;
}

// "depth_um" -> the factor of "um" as a length; throws naming the file and the column.
double column_unit(const std::string& header, std::string_view quantity, units::Dimension dimension,
                   std::string_view file, std::string_view example) {
  const std::string prefix = std::string(quantity) + "_";
  if (header.rfind(prefix, 0) != 0) {
    throw InvalidInput(fmt::format("{}:1: column '{}' is not a {} with its unit, expected e.g. '{}'", file, header,
                                   quantity, example));
  }
  return units::unit_factor(header.substr(prefix.size()), dimension, fmt::format("{}:1: column '{}'", file, header));
}

double number_of(const std::string& text, std::string_view file, int line, std::string_view column) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw InvalidInput(fmt::format("{}:{}: {} '{}' is not a number, expected a plain number in the header's unit",
                                   file, line, column, text));
  }
  return value;
}

}  // namespace

insertion::ForceDepthCurve parse_force_curve_csv(std::string_view text, std::string_view file) {
  std::istringstream in{std::string(text)};
  std::string line;
  if (!std::getline(in, line)) throw InvalidInput(fmt::format("{}:1: empty file, expected a header depth_um,force_N", file));
  const std::vector<std::string> header = fields_of(line);
  if (header.size() < 2) {
    throw InvalidInput(fmt::format("{}:1: header '{}' has fewer than two columns, expected depth_um,force_N", file, line));
  }
  const double depth_unit = column_unit(header[0], "depth", units::Dimension::Length, file, "depth_um");
  const double force_unit = column_unit(header[1], "force", units::Dimension::Force, file, "force_N");
  insertion::ForceDepthCurve curve;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \r") == std::string::npos) continue;
    const std::vector<std::string> fields = fields_of(line);
    if (fields.size() < 2) throw InvalidInput(fmt::format("{}:{}: fewer than two values, expected depth,force", file, number));
    const double depth = number_of(fields[0], file, number, header[0]) * depth_unit;
    if (!curve.depth.empty() && !(depth > curve.depth.back())) {
      throw InvalidInput(fmt::format("{}:{}: {} {} does not increase, expected strictly increasing depths", file,
                                     number, header[0], fields[0]));
    }
    curve.depth.push_back(depth);
    curve.force.push_back(number_of(fields[1], file, number, header[1]) * force_unit);
  }
  if (curve.depth.size() < 2) {
    throw InvalidInput(fmt::format("{}: {} rows, expected at least two (depth, force) rows", file, curve.depth.size()));
  }
  return curve;
}

insertion::ForceDepthCurve read_force_curve_csv(const std::filesystem::path& path) {
  return parse_force_curve_csv(config::read_text(path), path.string());
}

}  // namespace needlekit::io
