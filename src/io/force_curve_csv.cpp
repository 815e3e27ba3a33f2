#include "needlekit/io/force_curve_csv.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <tuple>
#include <string>
#include <vector>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/file_bytes.hpp"
#include "needlekit/core/units.hpp"

namespace needlekit::io {
namespace {

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t' || text.front() == '"')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r' || text.back() == '"'))
    text.remove_suffix(1);
  return text;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i)
    if (i == line.size() || line[i] == ',') {
      fields.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  return fields;
}

struct Column {
  int index = -1;
  double factor = 1;
};

}  // namespace

insertion::ForceDepthCurve parse_force_curve_csv(std::string_view text, std::string_view source_name) {
  std::istringstream in{std::string(text)};
  std::string line;
  int line_number = 0;
  Column depth, force;
  bool have_header = false;
  std::string header_text;
  insertion::ForceDepthCurve curve;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    const auto fields = split(content);
    if (!have_header) {
      have_header = true;
      header_text = std::string(content);
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::string_view name = fields[i];
        for (auto [prefix, column, dimension] :
             {std::tuple{std::string_view("depth_"), &depth, units::Dimension::Length},
              std::tuple{std::string_view("force_"), &force, units::Dimension::Force}}) {
          if (name.substr(0, prefix.size()) != prefix || column->index >= 0) continue;
          column->index = static_cast<int>(i);
          column->factor = units::unit_factor(name.substr(prefix.size()), dimension,
                                              fmt::format("{}:{}: column '{}'", source_name, line_number, name));
        }
      }
      for (auto [quantity, name, column] : {std::tuple{"depth", "depth_<unit> (e.g. depth_um)", &depth},
                                            std::tuple{"force", "force_<unit> (e.g. force_N)", &force}}) {
        if (column->index >= 0) continue;
        for (std::string_view field : fields)  // "depth" or "force" without its unit
          if (field == quantity)
            throw InvalidInput(fmt::format("{}:{}: column '{}' is not a {} with its unit, expected {}", source_name,
                                           line_number, field, quantity, name));
        throw InvalidInput(fmt::format("{}:{}: missing column {}; the header is '{}'", source_name, line_number, name,
                                       header_text));
      }
      continue;
    }
    double values[2] = {0, 0};
    const Column* columns[2] = {&depth, &force};
    for (int c = 0; c < 2; ++c) {
      const auto index = static_cast<std::size_t>(columns[c]->index);
      if (index >= fields.size())
        throw InvalidInput(fmt::format("{}:{}: {} fields, expected at least {} (as the header '{}')", source_name,
                                       line_number, fields.size(), index + 1, header_text));
      const std::string_view field = fields[index];
      double value = 0;
      const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
      if (error != std::errc() || end != field.data() + field.size() || !std::isfinite(value))
        throw InvalidInput(fmt::format("{}:{}: column {}: '{}' is not a number", source_name, line_number,
                                       index + 1, field));
      values[c] = value * columns[c]->factor;
    }
    if (!curve.depth.empty() && !(values[0] > curve.depth.back()))
      throw InvalidInput(fmt::format("{}:{}: depth is not monotonic: {:.6g} m after {:.6g} m, expected strictly "
                                     "increasing depths",
                                     source_name, line_number, values[0], curve.depth.back()));
    curve.depth.push_back(values[0]);
    curve.force.push_back(values[1]);
  }
  if (!have_header)
    throw InvalidInput(fmt::format("{}: empty, expected a header with depth_<unit> and force_<unit> columns",
                                   source_name));
  if (curve.depth.empty()) throw InvalidInput(fmt::format("{}: no samples after the header", source_name));
  return curve;
}

insertion::ForceDepthCurve read_force_curve_csv(const std::filesystem::path& path) {
  return parse_force_curve_csv(read_file_bytes(path, "force curve CSV"), path.string());
}

}  // namespace needlekit::io
