#include "needlekit/io/patch_config.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "needlekit/analysis/puncture_model.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/io/design_config.hpp"

namespace needlekit::io {
namespace {

using units::Dimension;

// Reads the keys of one table with FILE:LINE messages.
class Table {
public:
  Table(const toml::table& table, std::string name, std::string_view file,
        std::initializer_list<std::string_view> allowed)
      : table_(table), name_(std::move(name)), file_(file) {
    for (auto&& [key, node] : table_) {
      bool known = false;
      for (std::string_view a : allowed) known = known || key.str() == a;
      if (!known) {
        throw InvalidInput(fmt::format("{}:{}: unknown key '{}.{}', expected one of: {}", file_, key.source().begin.line,
                                       name_, key.str(), fmt::join(allowed, ", ")));
      }
    }
  }
  const toml::node* get(std::string_view key) const { return table_.get(key); }
  [[noreturn]] void fail(const toml::node* at, std::string_view key, std::string_view problem) const {
    const unsigned line = at ? at->source().begin.line : table_.source().begin.line;
    throw InvalidInput(fmt::format("{}:{}: key '{}.{}': {}", file_, line == 0 ? 1u : line, name_, key, problem));
  }
  const toml::node& required(std::string_view key, std::string_view expected) const {
    const toml::node* node = get(key);
    if (!node) fail(nullptr, key, fmt::format("missing (required in [{}]), expected {}", name_, expected));
    return *node;
  }
  std::string text(const toml::node& node, std::string_view key, std::string_view expected) const {
    if (!node.is_string()) fail(&node, key, fmt::format("is not a string, expected {}", expected));
    return node.as_string()->get();
  }
  double quantity(const toml::node& node, std::string_view key, Dimension dimension, std::string_view example) const {
    const std::string expected = fmt::format("a {} with its unit, e.g. {}", units::dimension_name(dimension), example);
    if (node.is_number()) fail(&node, key, fmt::format("is a bare number without a unit, expected {}", expected));
    const std::string value = text(node, key, expected);
    try {
      return units::parse_quantity(value, dimension, fmt::format("key '{}.{}'", name_, key));
    } catch (const InvalidInput& error) {
      fail(&node, key, error.what());
    }
  }
  double positive(const toml::node& node, std::string_view key, Dimension dimension, std::string_view example) const {
    const double value = quantity(node, key, dimension, example);
    if (!(value > 0)) {
      fail(&node, key, fmt::format("'{}' is not positive, expected a positive {}", node.as_string()->get(),
                                   units::dimension_name(dimension)));
    }
    return value;
  }
  template <class Call>
  auto at(const toml::node& node, std::string_view key, Call&& call) const {
    try {
      return call();
    } catch (const InvalidInput& error) {
      fail(&node, key, error.what());
    }
  }
  std::string_view file() const { return file_; }

private:
  const toml::table& table_;
  std::string name_;
  std::string_view file_;
};

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path)) {
    throw IoError(fmt::format("{}: cannot read: {}", path.string(), std::strerror(errno)));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const toml::table& table_of(const toml::table& root, std::string_view name, std::string_view file) {
  const toml::node* node = root.get(name);
  if (!node || !node->is_table()) {
    throw InvalidInput(fmt::format("{}:1: table [{}] is missing, expected a [{}] table", file, name, name));
  }
  return *node->as_table();
}

void read_surface(const Table& t, const std::filesystem::path& base, PatchCase& c) {
  c.mesh = base / t.text(t.required("mesh", "a mesh file name"), "mesh", "a mesh file name (OBJ, STL, PLY or OFF)");
  const toml::node& unit = t.required("unit", "the length of one file unit, e.g. \"mm\" or \"15.8 mm\"");
  const std::string unit_text = t.text(unit, "unit", "the length of one file unit, e.g. \"mm\" or \"15.8 mm\"");
  c.mesh_unit = t.at(unit, "unit", [&] {
    try {
      return units::unit_factor(unit_text, Dimension::Length, "surface.unit");
    } catch (const InvalidInput&) {
      return units::parse_quantity(unit_text, Dimension::Length, "surface.unit");
    }
  });
  if (!(c.mesh_unit > 0)) t.fail(&unit, "unit", "is not a positive length");
  const toml::node* vertex = t.get("center_vertex");
  const toml::node* center = t.get("center");
  if (vertex && center) t.fail(center, "center", "given together with center_vertex, expected one of them");
  if (!vertex && !center) {
    t.fail(nullptr, "center_vertex", "missing, expected center_vertex = <vertex index> or center = [\"x mm\", ...]");
  }
  if (vertex) {
    if (!vertex->is_integer() || vertex->as_integer()->get() < 0) {
      t.fail(vertex, "center_vertex", "is not a non-negative integer, expected a 0-based vertex index");
    }
    c.placement.center_vertex = static_cast<int>(vertex->as_integer()->get());
  } else {
    if (!center->is_array() || center->as_array()->size() != 3) {
      t.fail(center, "center", "is not a point, expected [\"x mm\", \"y mm\", \"z mm\"]");
    }
    for (int i = 0; i < 3; ++i) {
      c.placement.center[i] = t.quantity(*center->as_array()->get(i), "center", Dimension::Length, "\"64.5 mm\"");
    }
  }
  if (const toml::node* node = t.get("rotation")) {
    c.placement.rotation = t.quantity(*node, "rotation", Dimension::Angle, "\"30 deg\"");
  }
  if (const toml::node* node = t.get("approach")) {
    const std::string text = t.text(*node, "approach", "\"-z\" or \"normal\"");
    if (text == "-z") {
      c.placement.approach = patch::Approach::MinusZ;
    } else if (text == "normal") {
      c.placement.approach = patch::Approach::SurfaceNormal;
    } else {
      t.fail(node, "approach", fmt::format("unknown value '{}', expected \"-z\" or \"normal\"", text));
    }
  }
}

void read_patch(const Table& t, PatchCase& c) {
  const toml::node& kind = t.required("kind", "\"rigid\", \"flexible\" or \"equilibrium\"");
  const std::string kind_text = t.text(kind, "kind", "\"rigid\", \"flexible\" or \"equilibrium\"");
  c.fit.kind = t.at(kind, "kind", [&] { return patch::patch_kind_from_string(kind_text, "patch.kind"); });
  const double size = t.positive(t.required("size", "a length, e.g. \"10 mm\""), "size", Dimension::Length, "\"10 mm\"");
  c.design.width_u = c.design.width_v = size;
  const toml::node& count = t.required("needles_per_row", "an integer >= 2");
  if (!count.is_integer() || count.as_integer()->get() < 2 || count.as_integer()->get() > 10000) {
    t.fail(&count, "needles_per_row", "is not an integer in [2, 10000], expected e.g. 10");
  }
  c.design.needles_u = c.design.needles_v = static_cast<int>(count.as_integer()->get());
  const toml::node& spring = t.required("spring_constant", "a stiffness, e.g. \"1 N/mm\"");
  if (spring.is_table()) {
    const Table springs(*spring.as_table(), "patch.spring_constant", t.file(), {"u", "v", "diagonal"});
    auto one = [&](std::string_view key) {
      return springs.positive(springs.required(key, "a stiffness, e.g. \"1 N/mm\""), key, Dimension::Stiffness,
                              "\"1 N/mm\"");
    };
    c.design.stiffness_u = one("u");
    c.design.stiffness_v = one("v");
    c.design.stiffness_diagonal = one("diagonal");
  } else {
    c.design.stiffness_u = c.design.stiffness_v = c.design.stiffness_diagonal =
        t.positive(spring, "spring_constant", Dimension::Stiffness, "\"1 N/mm\"");
  }
  if (const toml::node* node = t.get("max_spring_energy")) {
    c.fit.flexible.max_spring_energy = t.positive(*node, "max_spring_energy", Dimension::Energy, "\"0.05 mJ\"");
  } else if (c.fit.kind == patch::PatchKind::Flexible) {
    t.fail(nullptr, "max_spring_energy", "missing for a flexible patch, expected an energy, e.g. \"0.05 mJ\"");
  }
  if (const toml::node* node = t.get("first_node")) {
    const std::string text = t.text(*node, "first_node", "\"first-contact\" or \"corner\"");
    if (text == "first-contact") {
      c.fit.flexible.first_node = patch::FirstNode::FirstContact;
    } else if (text == "corner") {
      c.fit.flexible.first_node = patch::FirstNode::Corner;
    } else {
      t.fail(node, "first_node", fmt::format("unknown value '{}', expected \"first-contact\" or \"corner\"", text));
    }
  }
  if (const toml::node* node = t.get("load")) {
    c.fit.equilibrium.node_load = t.positive(*node, "load", Dimension::Force, "\"0.0712 N\"");
    c.load_given = true;
  }
}

}  // namespace

PatchCase parse_patch_case_toml(std::string_view text, std::string_view source_name,
                                const std::filesystem::path& base_folder) {
  const std::string file(source_name);
  // [needle], [tissue], [insertion] as in design files; this also rejects unknown tables and bad TOML.
  const DesignFile needle = parse_needle_tables(text, file, {"surface", "patch"});
  const toml::table root = toml::parse(text, file);
  PatchCase c;
  read_surface(Table(table_of(root, "surface", file), "surface", file,
                     {"mesh", "unit", "center_vertex", "center", "rotation", "approach"}),
               base_folder, c);
  read_patch(Table(table_of(root, "patch", file), "patch", file,
                   {"kind", "size", "needles_per_row", "spring_constant", "max_spring_energy", "first_node", "load"}),
             c);
  c.design.needle = needle.design.needle;
  c.design.material = needle.design.material;
  c.evaluation.conditions = needle.conditions;
  c.evaluation.index = needle.options;
  if (!c.load_given) {
    // The force that punctures one needle, |F(A)| (Eq 4.2); at least 1 µN.
    c.fit.equilibrium.node_load = std::max(
        1e-6, std::abs(analysis::puncture_force(needle::tip_area(c.design.needle), c.evaluation.conditions.tissue)));
  }
  return c;
}

PatchCase read_patch_case(const std::filesystem::path& path) {
  return parse_patch_case_toml(read_text(path), path.string(), path.parent_path());
}

}  // namespace needlekit::io
