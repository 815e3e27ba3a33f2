#include "needlekit/io/design_config.hpp"

#include "config_tables.hpp"
#include "needlekit/io/toml_config.hpp"
#include "uncertainty_tables.hpp"

#include <algorithm>
#include <initializer_list>

namespace needlekit::io {
namespace {

using namespace config;  // the TOML reading helpers of toml_config.hpp

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
        choice_of(section, *node, "end_condition", analysis::kEndConditionNames);
  }
  if (const toml::node* node = section.optional("effective_length")) {
    file.options.buckling.effective_length =
        choice_of(section, *node, "effective_length", analysis::kEffectiveLengthNames);
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

// A design of the space at the smallest value of every range: the spreads of the design variables are checked
// against it (the smallest sizes are the first to go non-physical).
uncertainty::DesignCase smallest_design(const analysis::DesignSpace& space) {
  uncertainty::DesignCase c;
  c.design.needle = {space.shape, space.tip_diameter.min,
                     space.shape == needle::Shape::Cylinder ? space.tip_diameter.min : space.base_diameter.min,
                     space.hollow ? space.bore_diameter.min : 0.0, space.length.min};
  c.design.material = space.material;
  c.design.width = space.width.min;
  c.conditions = space.conditions;
  return c;
}

std::optional<RobustSpec> robust_spec_of(const toml::table& root, const Section& top, const std::string& file,
                                         const analysis::DesignSpace& space) {
  const toml::node* level = top.optional("min_success_probability");
  if (!level) {
    for (std::string_view table : {"uncertain", "sampling", "correlation"}) {
      if (const toml::node* node = top.optional(table)) {
        top.fail(*node, table, "given without min_success_probability, expected both (robust design) or neither");
      }
    }
    return std::nullopt;
  }
  RobustSpec spec;
  if (!level->is_number() || !(*level->value<double>() > 0 && *level->value<double>() <= 1)) {
    top.fail(*level, "min_success_probability", fmt::format("{} is not a probability in (0, 1]", describe(*level)));
  }
  spec.min_success_probability = *level->value<double>();
  UncertaintyTables tables = read_uncertainty_tables(root, file);
  spec.inputs = std::move(tables.inputs);
  spec.correlations = std::move(tables.correlations);
  spec.sampling = tables.sampling;
  const toml::table& uncertain = *root.get("uncertain")->as_table();
  for (const uncertainty::DesignUncertainInput& input : spec.inputs) {
    const uncertainty::DesignInput which = uncertainty::design_input_from_key(input.key, input.key);
    const bool design_variable = which == uncertainty::DesignInput::TipDiameter ||
                                 which == uncertainty::DesignInput::BaseDiameter ||
                                 which == uncertainty::DesignInput::BoreDiameter ||
                                 which == uncertainty::DesignInput::Length || which == uncertainty::DesignInput::Width;
    if (design_variable && !input.centred_on_nominal) {
      const toml::node* node = uncertain.get(input.key);
      throw InvalidInput(fmt::format("{} key 'uncertain.\"{}\"': a design variable's spread is centred on every "
                                     "candidate, expected a normal, truncated-normal or lognormal without mean or median",
                                     location(file, (node ? node : &uncertain)->source()), input.key));
    }
  }
  std::vector<std::string> notes;
  validate_at_keys(root, file, uncertain, [&] {
    uncertainty::design_input_transform(smallest_design(space), spec.inputs, spec.correlations, notes);
  });
  return spec;
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

  if (const auto tissue = top.optional_subsection("tissue", {"model", "puncture_force"})) {
    result.conditions.tissue = tissue_model_of(*tissue, "model");
    result.conditions.tissue.force_law = puncture_force_law_of(*tissue, "puncture_force");
  }
  if (const auto insertion = top.optional_subsection(
          "insertion", {"angle", "target_depth", "application", "buckling_safety_factor", "bending_safety_factor",
                        "end_condition", "effective_length", "johnson"})) {
    read_insertion(*insertion, result);
    // Options of the uniform-column formulas (Eqs 2.28, 2.35) do not apply to a cone's or a bevel's tapered column
    // (Eq 2.36 with m computed from its exact end conditions): an error, not silently ignored.
    if (result.design.needle.shape != needle::Shape::Cylinder) {
      for (std::string_view key : {"effective_length", "johnson"}) {
        if (const toml::node* node = insertion->optional(key)) {
          insertion->fail(*node, key,
                          fmt::format("does not apply to a {}: it selects a uniform column's formula (cylinders "
                                      "only), while a {}'s buckling load is the eigenvalue of its own tapered column; "
                                      "remove it",
                                      needle::to_string(result.design.needle.shape),
                                      needle::to_string(result.design.needle.shape)));
        }
      }
    }
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
  return config::design_of_table(parse_toml(text, file), file);
}

DesignFile config::design_of_table(const toml::table& root, const std::string& file) {
  const Section top(root, "", file, {"needle", "array", "tissue", "insertion"});
  return read_needle_tables(root, top, file, true);
}

namespace {

// The design tables of a file that also holds `other_tables` (read by the caller); any other table is an error.
DesignFile parse_tables(std::string_view text, std::string_view source_name,
                        std::initializer_list<std::string_view> other_tables, bool with_array) {
  const std::string file(source_name);
  return config::design_of_tables(parse_toml(text, file), file, other_tables, with_array);
}

}  // namespace

DesignFile config::design_of_tables(const toml::table& root, const std::string& file,
                                    std::initializer_list<std::string_view> other_tables, bool with_array) {
  std::vector<std::string_view> own_tables{"needle", "tissue", "insertion"};
  if (with_array) own_tables.push_back("array");
  std::vector<std::string_view> allowed = own_tables;
  allowed.insert(allowed.end(), other_tables.begin(), other_tables.end());
  for (auto&& [key, node] : root) {
    if (std::find(allowed.begin(), allowed.end(), key.str()) == allowed.end()) {
      throw InvalidInput(fmt::format("{} unknown table '{}', expected one of: {}", location(file, key.source()),
                                     key.str(), fmt::join(allowed, ", ")));
    }
  }
  toml::table own;
  for (std::string_view name : own_tables) {
    if (const toml::node* node = root.get(name)) own.insert(name, *node);
  }
  const Section top(own, "", file, {"needle", "tissue", "insertion", "array"});
  return read_needle_tables(root, top, file, with_array);
}

DesignFile parse_needle_tables(std::string_view text, std::string_view source_name,
                               std::initializer_list<std::string_view> other_tables) {
  return parse_tables(text, source_name, other_tables, false);
}

DesignFile parse_design_tables(std::string_view text, std::string_view source_name,
                               std::initializer_list<std::string_view> other_tables) {
  return parse_tables(text, source_name, other_tables, true);
}

DesignFile read_design_file(const std::filesystem::path& path) {
  return parse_design_toml(read_text(path), path.string());
}

SpaceFile parse_space_toml(std::string_view text, std::string_view source_name) {
  const std::string file(source_name);
  return config::space_of_table(parse_toml(text, file), file);
}

SpaceFile config::space_of_table(const toml::table& root, const std::string& file) {
  const Section top(root, "", file,
                    {"shape", "hollow", "material", "tissue", "puncture_force", "target_depth", "spacing_factor",
                     "ranges", "min_success_probability", "uncertain", "sampling", "correlation"});

  SpaceFile result;
  analysis::DesignSpace& space = result.space;
  space.shape = shape_of(top, "shape");
  if (const toml::node* node = top.optional("hollow")) space.hollow = boolean_of(top, *node, "hollow");
  space.material = material_of(top, "material");
  space.conditions.tissue = tissue_model_of(top, "tissue");
  space.conditions.tissue.force_law = puncture_force_law_of(top, "puncture_force");
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
  result.robust = robust_spec_of(root, top, file, space);
  return result;
}

SpaceFile read_space_file(const std::filesystem::path& path) {
  return parse_space_toml(read_text(path), path.string());
}

}  // namespace needlekit::io
