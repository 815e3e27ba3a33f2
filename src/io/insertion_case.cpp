#include "needlekit/io/insertion_case.hpp"

#include <fstream>
#include <sstream>

#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/io/force_curve_csv.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/toml_config.hpp"
#include "needlekit/io/toml_parameters.hpp"

namespace needlekit::io {
namespace {

using config::Section;

bool is_header_of(std::string_view line, std::string_view table) {
  const std::size_t start = line.find_first_not_of(" \t");
  if (start == std::string_view::npos || line[start] != '[' || line.substr(start, 2) == "[[") return false;
  std::string_view name = line.substr(start + 1);
  name = name.substr(0, name.find(']'));
  while (!name.empty() && (name.front() == ' ' || name.front() == '\t')) name.remove_prefix(1);
  while (!name.empty() && (name.back() == ' ' || name.back() == '\t')) name.remove_suffix(1);
  return name == table || name.substr(0, table.size() + 1) == std::string(table) + ".";
}

// The text with the given tables' lines blanked (each table runs to the next table header).
std::string without_tables(std::string_view text, std::initializer_list<std::string_view> tables) {
  std::istringstream in{std::string(text)};
  std::string out, line;
  bool skipping = false;
  while (std::getline(in, line)) {
    const std::size_t start = line.find_first_not_of(" \t");
    if (start != std::string::npos && line[start] == '[') {
      skipping = false;
      for (std::string_view table : tables) skipping = skipping || is_header_of(line, table);
    }
    out += skipping ? std::string() : line;
    out += '\n';
  }
  return out;
}

// [post_puncture]'s keys: the rows of the fit's and the curve's tables, of insertion::kPostPunctureParameters and of
// the classification's, then the measured curve, in the order the messages have always listed them.
std::vector<std::string_view> post_puncture_keys() {
  std::vector<std::string_view> keys;
  InsertionSettings settings;
  for_each_post_puncture_table(settings, [&keys](const auto& table, const auto&) {
    const std::vector<std::string_view> rows = config::keys_of_group(table, "post_puncture");
    keys.insert(keys.end(), rows.begin(), rows.end());
  });
  keys.push_back("measured");
  return keys;
}

}  // namespace

InsertionSettings parse_insertion_settings(std::string_view text, std::string_view source_name,
                                           const std::filesystem::path& base_directory) {
  const toml::table root = config::parse_toml(text, source_name);
  const toml::node* post_node = root.get("post_puncture");
  if (!post_node)
    throw InvalidInput(fmt::format("{}:1: missing table [post_puncture] (required), expected stiffness, scale and "
                                   "final_depth of the cutting phase",
                                   source_name));
  if (!post_node->is_table())
    throw InvalidInput(fmt::format("{} key 'post_puncture': expected a table [post_puncture]",
                                   config::location(source_name, post_node->source())));
  const Section post(*post_node->as_table(), "post_puncture", source_name, post_puncture_keys());
  InsertionSettings settings;
  for_each_post_puncture_table(settings, [&post](const auto& table, auto& options) {
    config::read_parameters(post, table, "post_puncture", options);
  });
  if (const toml::node* node = post.optional("measured"))
    settings.measured = base_directory / config::text_of(post, *node, "measured", "a CSV file name");

  if (const toml::node* pre_node = root.get("pre_puncture")) {
    if (!pre_node->is_table())
      throw InvalidInput(fmt::format("{} key 'pre_puncture': expected a table [pre_puncture]",
                                     config::location(source_name, pre_node->source())));
    const Section pre(*pre_node->as_table(), "pre_puncture", source_name, {"curve", "punctured"});
    const toml::node& curve_node = pre.required("curve", "a CSV file with depth_<unit> and force_<unit> columns");
    const std::filesystem::path path = base_directory / config::text_of(pre, curve_node, "curve", "a CSV file name");
    insertion::PrePunctureCurve curve;
    curve.curve = read_force_curve_csv(path);
    if (curve.curve.depth.front() < 0)
      pre.fail(curve_node, "curve", fmt::format("{}: the first depth is negative, expected depths >= 0", path.string()));
    bool punctured = true;
    if (const toml::node* node = pre.optional("punctured")) punctured = config::boolean_of(pre, *node, "punctured");
    if (punctured) {
      if (!(curve.curve.depth.back() > 0))
        pre.fail(curve_node, "curve", fmt::format("{}: the puncture depth (last sample) is 0", path.string()));
      curve.puncture = insertion::PuncturePoint{curve.curve.depth.back(), curve.curve.force.back(),
                                                insertion::PunctureCriterion::None};
    }
    settings.pre_puncture = std::move(curve);
  }
  if (const toml::node* needle = root.get("needle"); needle && needle->is_table())
    if (const toml::node* mesh = needle->as_table()->get("mesh"); mesh && mesh->is_string())
      settings.needle_mesh = base_directory / mesh->as_string()->get();
  settings.indentation_text = without_tables(text, {"post_puncture", "pre_puncture"});
  return settings;
}

InsertionCase read_insertion_case(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError(fmt::format("{}: cannot read", path.string()));
  std::stringstream text;
  text << in.rdbuf();
  const std::filesystem::path base = path.has_parent_path() ? path.parent_path() : ".";
  InsertionSettings settings = parse_insertion_settings(text.str(), path.string(), base);
  if (settings.needle_mesh)  // open, non-manifold or inverted: say so
    insertion::validate_needle_surface(geometry::read_triangle_mesh(*settings.needle_mesh, 1.0),
                                       settings.needle_mesh->string());
  InsertionCase c;
  c.indentation = parse_indentation_case_toml(settings.indentation_text, path.string(), base);
  insertion::CompleteInsertionOptions& o = c.options;
  o.model = settings.model;
  o.post_puncture = settings.post_puncture;
  o.classification = settings.classification;
  o.curve = settings.curve;
  o.pre_puncture = std::move(settings.pre_puncture);
  if (settings.measured) {
    o.measured = read_force_curve_csv(*settings.measured);
    c.measured = settings.measured;
  }
  return c;
}

}  // namespace needlekit::io
