#include "needlekit/io/design_config.hpp"

#include <toml++/toml.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "needlekit/analysis/skin_permeation.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"

namespace needlekit::io {
namespace {

using units::Dimension;

static_assert(TOML_EXCEPTIONS, "the config reader relies on toml::parse throwing toml::parse_error");

// "FILE:LINE:" of a node (line 1 when toml++ knows no position, e.g. for the root table).
std::string location(std::string_view file, const toml::source_region& region) {
  return fmt::format("{}:{}:", file, region.begin.line == 0 ? 1u : region.begin.line);
}

std::string_view example_of(Dimension dimension) {
  switch (dimension) {
    case Dimension::Length: return "\"70 um\"";
    case Dimension::Pressure: return "\"169 GPa\"";
    case Dimension::Force: return "\"0.0183 N\"";
    case Dimension::InverseLength: return "\"6.25 /mm\"";
    case Dimension::Angle: return "\"10 deg\"";
    default: return "\"1\"";
  }
}

std::string expected_quantity(Dimension dimension) {
  return fmt::format("a {} with its unit, e.g. {}", units::dimension_name(dimension), example_of(dimension));
}

// What a node is, for "... is <this>, expected ..." messages.
std::string describe(const toml::node& node) {
  if (node.is_string()) return fmt::format("the string \"{}\"", node.as_string()->get());
  if (node.is_integer()) return std::to_string(node.as_integer()->get());
  if (node.is_floating_point()) return fmt::format("{}", node.as_floating_point()->get());
  if (node.is_boolean()) return node.as_boolean()->get() ? "true" : "false";
  if (node.is_table()) return "a table";
  if (node.is_array()) return "an array";
  return "a date or time";
}

// One TOML table of the file, under its dotted key path. Unknown keys are rejected on construction, so a typo is
// reported as such rather than as a missing key.
class Section {
public:
  Section(const toml::table& table, std::string path, std::string_view file,
          std::initializer_list<std::string_view> allowed_keys)
      : table_(table), path_(std::move(path)), file_(file) {
    for (auto&& [key, node] : table_) {
      bool known = false;
      for (std::string_view allowed : allowed_keys) known = known || key.str() == allowed;
      if (!known) {
        throw InvalidInput(fmt::format("{} unknown key '{}', expected one of: {}", location(file_, key.source()),
                                       key_path(key.str()), fmt::join(allowed_keys, ", ")));
      }
    }
  }

  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
  }
  std::string_view file() const { return file_; }
  const toml::table& table() const { return table_; }

  [[noreturn]] void fail(const toml::node& at, std::string_view key, std::string_view problem) const {
    throw InvalidInput(fmt::format("{} key '{}': {}", location(file_, at.source()), key_path(key), problem));
  }

  const toml::node* optional(std::string_view key) const { return table_.get(key); }

  const toml::node& required(std::string_view key, std::string_view expected) const {
    const toml::node* node = table_.get(key);
    if (!node) {
      fail(table_, key,
           fmt::format("missing (required{}), expected {}",
                       path_.empty() ? std::string() : fmt::format(" in [{}]", path_), expected));
    }
    return *node;
  }

  Section subsection(const toml::node& node, std::string_view key,
                     std::initializer_list<std::string_view> allowed_keys) const {
    if (!node.is_table()) {
      fail(node, key, fmt::format("{} is not a table, expected a table with keys {}", describe(node),
                                  fmt::join(allowed_keys, ", ")));
    }
    return Section(*node.as_table(), key_path(key), file_, allowed_keys);
  }

  Section required_subsection(std::string_view key, std::initializer_list<std::string_view> allowed_keys) const {
    return subsection(required(key, fmt::format("a table [{}]", key_path(key))), key, allowed_keys);
  }

  std::optional<Section> optional_subsection(std::string_view key,
                                             std::initializer_list<std::string_view> allowed_keys) const {
    const toml::node* node = optional(key);
    if (!node) return std::nullopt;
    return subsection(*node, key, allowed_keys);
  }

  // Runs a library call that throws InvalidInput naming `what`, and prefixes its message with FILE:LINE.
  template <class Call>
  auto at(const toml::node& node, Call&& call) const {
    try {
      return call();
    } catch (const InvalidInput& error) {
      throw InvalidInput(fmt::format("{} {}", location(file_, node.source()), error.what()));
    }
  }

  std::string what(std::string_view key) const { return fmt::format("key '{}'", key_path(key)); }

private:
  const toml::table& table_;
  std::string path_;
  std::string_view file_;
};

// ---- values -------------------------------------------------------------------------------------------------------

std::string text_of(const Section& section, const toml::node& node, std::string_view key, std::string_view expected) {
  if (!node.is_string()) section.fail(node, key, fmt::format("{} is not a string, expected {}", describe(node), expected));
  return node.as_string()->get();
}

double quantity_of(const Section& section, const toml::node& node, std::string_view key, Dimension dimension) {
  if (node.is_number()) {
    section.fail(node, key,
                 fmt::format("{} is a bare number without a unit, expected {}", describe(node), expected_quantity(dimension)));
  }
  if (!node.is_string()) {
    section.fail(node, key, fmt::format("{} is not a quantity, expected {}", describe(node), expected_quantity(dimension)));
  }
  const std::string text = node.as_string()->get();
  return section.at(node, [&] { return units::parse_quantity(text, dimension, section.what(key)); });
}

double positive_quantity_of(const Section& section, const toml::node& node, std::string_view key,
                            Dimension dimension) {
  const double value = quantity_of(section, node, key, dimension);
  if (!(value > 0)) {
    section.fail(node, key,
                 fmt::format("'{}' is not positive, expected a positive {}", node.as_string()->get(),
                             units::dimension_name(dimension)));
  }
  return value;
}

double positive_quantity(const Section& section, std::string_view key, Dimension dimension) {
  return positive_quantity_of(section, section.required(key, expected_quantity(dimension)), key, dimension);
}

std::optional<double> optional_positive_quantity(const Section& section, std::string_view key, Dimension dimension) {
  const toml::node* node = section.optional(key);
  if (!node) return std::nullopt;
  return positive_quantity_of(section, *node, key, dimension);
}

// A plain number (integer or float) >= minimum.
double number_at_least(const Section& section, const toml::node& node, std::string_view key, double minimum) {
  if (!node.is_number()) {
    section.fail(node, key, fmt::format("{} is not a number, expected a number >= {}", describe(node), minimum));
  }
  const double value = *node.value<double>();
  if (!std::isfinite(value) || !(value >= minimum)) {
    section.fail(node, key, fmt::format("{} is out of range, expected a number >= {}", describe(node), minimum));
  }
  return value;
}

std::int64_t integer_of(const Section& section, const toml::node& node, std::string_view key) {
  if (!node.is_integer()) {
    section.fail(node, key, fmt::format("{} is not an integer, expected an integer", describe(node)));
  }
  return node.as_integer()->get();
}

int integer_at_least(const Section& section, const toml::node& node, std::string_view key, int minimum) {
  const std::int64_t value = integer_of(section, node, key);
  if (value < minimum || value > INT_MAX) {
    section.fail(node, key, fmt::format("{} is out of range, expected an integer >= {}", value, minimum));
  }
  return static_cast<int>(value);
}

bool boolean_of(const Section& section, const toml::node& node, std::string_view key) {
  if (!node.is_boolean()) section.fail(node, key, fmt::format("{} is not a boolean, expected true or false", describe(node)));
  return node.as_boolean()->get();
}

template <class Value>
Value choice_of(const Section& section, const toml::node& node, std::string_view key,
                std::initializer_list<std::pair<std::string_view, Value>> choices) {
  std::vector<std::string_view> names;
  for (const auto& [name, value] : choices) names.push_back(name);
  const std::string text = text_of(section, node, key, fmt::format("one of: {}", fmt::join(names, ", ")));
  for (const auto& [name, value] : choices) {
    if (text == name) return value;
  }
  section.fail(node, key, fmt::format("unknown value '{}', expected one of: {}", text, fmt::join(names, ", ")));
}

// ---- the parts shared by both files -------------------------------------------------------------------------------

needle::Shape shape_of(const Section& section, std::string_view key) {
  const toml::node& node = section.required(key, "\"cylinder\", \"cone\" or \"bevel\"");
  const std::string text = text_of(section, node, key, "\"cylinder\", \"cone\" or \"bevel\"");
  return section.at(node, [&] { return needle::shape_from_string(text, section.what(key)); });
}

materials::NeedleMaterial material_of(const Section& parent, std::string_view key) {
  const std::string expected =
      fmt::format("a preset name ({}) or an inline table {{ youngs_modulus = \"4 GPa\", yield_strength = \"60 MPa\", "
                  "allowable_stress = \"40 MPa\", name = \"...\" }}",
                  fmt::join(materials::material_preset_names(), ", "));
  const toml::node& node = parent.required(key, expected);
  if (node.is_string()) {
    const std::string name = node.as_string()->get();
    return parent.at(node, [&] { return materials::material_preset(name, parent.what(key)); });
  }
  if (!node.is_table()) parent.fail(node, key, fmt::format("{} is not a material, expected {}", describe(node), expected));
  const Section table =
      parent.subsection(node, key, {"name", "youngs_modulus", "yield_strength", "allowable_stress"});
  materials::NeedleMaterial material;
  material.name = "custom";
  if (const toml::node* name = table.optional("name")) material.name = text_of(table, *name, "name", "a name");
  material.youngs_modulus = positive_quantity(table, "youngs_modulus", Dimension::Pressure);
  material.yield_strength = optional_positive_quantity(table, "yield_strength", Dimension::Pressure);
  material.allowable_stress = optional_positive_quantity(table, "allowable_stress", Dimension::Pressure);
  material.source = fmt::format("inline table in {}", parent.file());
  return material;
}

// A preset name or a table { alpha, tau, small_tip_slope?, name? }; skin when the key is absent.
analysis::PunctureModel tissue_model_of(const Section& parent, std::string_view key) {
  const toml::node* node = parent.optional(key);
  if (!node) return analysis::skin_puncture_model();
  if (node->is_string()) {
    const std::string name = node->as_string()->get();
    return parent.at(*node, [&] { return analysis::puncture_model_preset(name, parent.what(key)); });
  }
  if (!node->is_table()) {
    parent.fail(*node, key,
                fmt::format("{} is not a tissue model, expected \"skin\", \"brain\" or a table {{ alpha = \"0.0183 N\", "
                            "tau = \"6.25 /mm\" }}",
                            describe(*node)));
  }
  const Section table = parent.subsection(*node, key, {"name", "alpha", "tau", "small_tip_slope"});
  analysis::PunctureModel model = analysis::skin_puncture_model();  // Eq 4.2's F(A) line and K are skin's
  model.name = "custom";
  if (const toml::node* name = table.optional("name")) model.name = text_of(table, *name, "name", "a name");
  model.alpha = positive_quantity(table, "alpha", Dimension::Force);
  model.tau = positive_quantity(table, "tau", Dimension::InverseLength);
  if (auto slope = optional_positive_quantity(table, "small_tip_slope", Dimension::InverseLength)) {
    model.small_tip_slope = *slope;
  }
  return model;
}

// Runs the library's validation and re-throws its InvalidInput at the line of the key it names ("needle.length: ...")
// when that key is in the file, otherwise at `fallback`'s line.
template <class Validation>
void validate_at_keys(const toml::table& root, std::string_view file, const toml::node& fallback,
                      Validation&& validation) {
  try {
    validation();
  } catch (const InvalidInput& error) {
    const std::string_view message = error.what();
    const std::size_t colon = message.find(": ");
    if (colon != std::string_view::npos) {
      const std::string_view key = message.substr(0, colon);
      if (const toml::node* node = root.at_path(key).node()) {
        throw InvalidInput(
            fmt::format("{} key '{}': {}", location(file, node->source()), key, message.substr(colon + 2)));
      }
    }
    throw InvalidInput(fmt::format("{} {}", location(file, fallback.source()), message));
  }
}

std::string read_text(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw IoError(fmt::format("{}: cannot read: it is a directory", path.string()));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot read: {}", path.string(), std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError(fmt::format("{}: cannot read: {}", path.string(), std::strerror(errno)));
  return text.str();
}

toml::table parse_toml(std::string_view text, std::string_view file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& error) {
    throw IoError(fmt::format("{}:{}:{}: invalid TOML: {}", file, error.source().begin.line,
                              error.source().begin.column, error.description()));
  }
}

// ---- design file --------------------------------------------------------------------------------------------------

needle::NeedleGeometry needle_of(const Section& section) {
  needle::NeedleGeometry geometry;
  geometry.shape = shape_of(section, "shape");
  geometry.tip_diameter = positive_quantity(section, "tip_diameter", Dimension::Length);
  if (geometry.shape == needle::Shape::Cylinder) {
    geometry.base_diameter = optional_positive_quantity(section, "base_diameter", Dimension::Length)
                                 .value_or(geometry.tip_diameter);
  } else {
    geometry.base_diameter = positive_quantity(section, "base_diameter", Dimension::Length);
  }
  geometry.bore_diameter = optional_positive_quantity(section, "bore_diameter", Dimension::Length).value_or(0.0);
  geometry.length = positive_quantity(section, "length", Dimension::Length);
  return geometry;
}

void read_insertion(const Section& section, DesignFile& file) {
  if (const toml::node* node = section.optional("angle")) {
    const double angle = quantity_of(section, *node, "angle", Dimension::Angle);
    if (!(angle >= 0 && angle < M_PI / 2)) {
      section.fail(*node, "angle", fmt::format("'{}' is out of range, expected an angle in [0, 90) deg",
                                               node->as_string()->get()));
    }
    file.conditions.angle = angle;
  }
  const toml::node* depth = section.optional("target_depth");
  const toml::node* application = section.optional("application");
  if (depth && application) {
    section.fail(*application, "application",
                 "given together with target_depth, expected one of target_depth or application");
  }
  if (depth) file.conditions.target_depth = positive_quantity_of(section, *depth, "target_depth", Dimension::Length);
  if (application) {
    const std::string name =
        text_of(section, *application, "application", "\"transdermal\", \"aesthetic\", \"tattoo\" or \"brain\"");
    file.conditions.target_depth =
        section.at(*application, [&] { return analysis::application_target_depth(name, section.what("application")); });
  }
  if (const toml::node* node = section.optional("buckling_safety_factor")) {
    file.options.buckling_safety_factor = number_at_least(section, *node, "buckling_safety_factor", 1.0);
  }
  if (const toml::node* node = section.optional("bending_safety_factor")) {
    file.options.bending_safety_factor = number_at_least(section, *node, "bending_safety_factor", 1.0);
  }
  if (const toml::node* node = section.optional("end_condition")) {
    file.options.buckling.end_condition =
        choice_of<analysis::EndCondition>(section, *node, "end_condition",
                                          {{"fixed-free", analysis::EndCondition::FixedFree},
                                           {"fixed-pinned", analysis::EndCondition::FixedPinned},
                                           {"fixed-fixed", analysis::EndCondition::FixedFixed}});
  }
  if (const toml::node* node = section.optional("effective_length")) {
    file.options.buckling.effective_length =
        choice_of<analysis::EffectiveLengthValue>(section, *node, "effective_length",
                                                  {{"theoretical", analysis::EffectiveLengthValue::Theoretical},
                                                   {"practical", analysis::EffectiveLengthValue::Practical}});
  }
  if (const toml::node* node = section.optional("johnson")) {
    file.options.buckling.johnson_for_short_columns = boolean_of(section, *node, "johnson");
  }
}

// ---- design-space file --------------------------------------------------------------------------------------------

// [min, max, step]: integers for a dimensionless range (needles_per_row), strings with units otherwise.
analysis::GridRange range_of(const Section& section, std::string_view key, Dimension dimension) {
  const bool counts = dimension == Dimension::Dimensionless;
  const std::string expected = counts ? "[min, max, step] of integers, e.g. [5, 25, 1]"
                                      : fmt::format("[min, max, step] of {}s with units, e.g. [\"30 um\", "
                                                    "\"150 um\", \"10 um\"]",
                                                    units::dimension_name(dimension));
  const toml::node& node = section.required(key, expected);
  if (!node.is_array() || node.as_array()->size() != 3) {
    section.fail(node, key, fmt::format("{} is not a [min, max, step] triple, expected {}", describe(node), expected));
  }
  const toml::array& array = *node.as_array();
  constexpr std::string_view kParts[] = {"min", "max", "step"};
  double values[3];
  std::string texts[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const toml::node& element = *array.get(i);
    const std::string part = fmt::format("{} ({})", key, kParts[i]);
    if (counts) {
      const std::int64_t value = integer_of(section, element, part);
      values[i] = static_cast<double>(value);
      texts[i] = std::to_string(value);
    } else {
      values[i] = quantity_of(section, element, part, dimension);
      texts[i] = element.as_string()->get();
    }
  }
  if (!(values[2] > 0)) {
    section.fail(*array.get(2), key, fmt::format("step '{}' is not positive, expected a step > 0", texts[2]));
  }
  if (!(values[0] > 0)) {
    section.fail(*array.get(0), key, fmt::format("min '{}' is not positive, expected a min > 0", texts[0]));
  }
  if (values[1] < values[0]) {
    section.fail(node, key,
                 fmt::format("empty range: max '{}' < min '{}', expected min <= max", texts[1], texts[0]));
  }
  return {values[0], values[1], values[2]};
}

bool same_range(const analysis::GridRange& a, const analysis::GridRange& b) {
  return a.min == b.min && a.max == b.max && a.step == b.step;
}

void read_ranges(const Section& ranges, analysis::DesignSpace& space) {
  space.needles_per_row = range_of(ranges, "needles_per_row", Dimension::Dimensionless);
  space.tip_diameter = range_of(ranges, "tip_diameter", Dimension::Length);
  if (space.shape == needle::Shape::Cylinder) {
    if (const toml::node* node = ranges.optional("base_diameter")) {
      if (!same_range(range_of(ranges, "base_diameter", Dimension::Length), space.tip_diameter)) {
        ranges.fail(*node, "base_diameter",
                    "differs from tip_diameter, expected no base_diameter for a cylinder (D2 = D1) or the same range");
      }
    }
    space.base_diameter = space.tip_diameter;
  } else {
    space.base_diameter = range_of(ranges, "base_diameter", Dimension::Length);
  }
  if (space.hollow) {
    space.bore_diameter = range_of(ranges, "bore_diameter", Dimension::Length);
  } else if (const toml::node* node = ranges.optional("bore_diameter")) {
    ranges.fail(*node, "bore_diameter", "given for solid needles, expected hollow = true or no bore_diameter");
  }
  space.width = range_of(ranges, "width", Dimension::Length);
  space.length = range_of(ranges, "length", Dimension::Length);
}

}  // namespace

namespace {

// [needle], [tissue] and [insertion] (and [array] when `with_array`), shared by design files and patch case files.
DesignFile read_needle_tables(const toml::table& root, const Section& top, const std::string& file, bool with_array) {
  DesignFile result;
  const Section needle =
      top.required_subsection("needle", {"shape", "tip_diameter", "base_diameter", "bore_diameter", "length", "material"});
  result.design.needle = needle_of(needle);
  result.design.material = material_of(needle, "material");

  if (with_array) {
    const Section array = top.required_subsection("array", {"needles_per_row", "width", "spacing_factor"});
    result.design.needles_per_row =
        integer_at_least(array, array.required("needles_per_row", "an integer >= 1"), "needles_per_row", 1);
    result.design.width = positive_quantity(array, "width", Dimension::Length);
    if (const toml::node* node = array.optional("spacing_factor")) {
      result.options.spacing_factor = number_at_least(array, *node, "spacing_factor", 0.0);
    }
  }

  if (const auto tissue = top.optional_subsection("tissue", {"model"})) {
    result.conditions.tissue = tissue_model_of(*tissue, "model");
  }
  if (const auto insertion = top.optional_subsection(
          "insertion", {"angle", "target_depth", "application", "buckling_safety_factor", "bending_safety_factor",
                        "end_condition", "effective_length", "johnson"})) {
    read_insertion(*insertion, result);
  }

  validate_at_keys(root, file, needle.table(), [&] {
    needle::validate(result.design.needle, "needle");
    materials::validate(result.design.material, "needle.material");
    analysis::validate(result.conditions.tissue, "tissue.model");
  });
  return result;
}

}  // namespace

DesignFile parse_design_toml(std::string_view text, std::string_view source_name) {
  const std::string file(source_name);
  const toml::table root = parse_toml(text, file);
  const Section top(root, "", file, {"needle", "array", "tissue", "insertion"});
  return read_needle_tables(root, top, file, true);
}

DesignFile parse_needle_tables(std::string_view text, std::string_view source_name,
                               std::initializer_list<std::string_view> other_tables) {
  const std::string file(source_name);
  const toml::table root = parse_toml(text, file);
  std::vector<std::string_view> allowed{"needle", "tissue", "insertion"};
  allowed.insert(allowed.end(), other_tables.begin(), other_tables.end());
  for (auto&& [key, node] : root) {
    if (std::find(allowed.begin(), allowed.end(), key.str()) == allowed.end()) {
      throw InvalidInput(fmt::format("{} unknown table '{}', expected one of: {}", location(file, key.source()),
                                     key.str(), fmt::join(allowed, ", ")));
    }
  }
  toml::table own;
  for (std::string_view name : {"needle", "tissue", "insertion"}) {
    if (const toml::node* node = root.get(name)) own.insert(name, *node);
  }
  const Section top(own, "", file, {"needle", "tissue", "insertion"});
  return read_needle_tables(root, top, file, false);
}

DesignFile read_design_file(const std::filesystem::path& path) {
  return parse_design_toml(read_text(path), path.string());
}

SpaceFile parse_space_toml(std::string_view text, std::string_view source_name) {
  const std::string file(source_name);
  const toml::table root = parse_toml(text, file);
  const Section top(root, "", file,
                    {"shape", "hollow", "material", "tissue", "target_depth", "spacing_factor", "ranges"});

  SpaceFile result;
  analysis::DesignSpace& space = result.space;
  space.shape = shape_of(top, "shape");
  if (const toml::node* node = top.optional("hollow")) space.hollow = boolean_of(top, *node, "hollow");
  space.material = material_of(top, "material");
  space.conditions.tissue = tissue_model_of(top, "tissue");
  if (const auto depth = optional_positive_quantity(top, "target_depth", Dimension::Length)) {
    space.conditions.target_depth = *depth;
  }
  if (const toml::node* node = top.optional("spacing_factor")) {
    space.spacing_factor = number_at_least(top, *node, "spacing_factor", 0.0);
  }
  read_ranges(top.required_subsection(
                  "ranges", {"needles_per_row", "tip_diameter", "base_diameter", "bore_diameter", "width", "length"}),
              space);

  validate_at_keys(root, file, root, [&] {
    materials::validate(space.material, "material");
    analysis::validate(space.conditions.tissue, "tissue");
    analysis::design_space_size(space);
  });
  return result;
}

SpaceFile read_space_file(const std::filesystem::path& path) {
  return parse_space_toml(read_text(path), path.string());
}

}  // namespace needlekit::io
