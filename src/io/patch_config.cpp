#include "needlekit/io/patch_config.hpp"

#include <algorithm>
#include <cmath>

#include "needlekit/io/design_config.hpp"
#include "config_tables.hpp"
#include "needlekit/io/toml_config.hpp"
#include "needlekit/patch/fit_parameters.hpp"
#include "needlekit/io/toml_parameters.hpp"

namespace needlekit::io {
namespace {

using namespace config;  // the TOML reading helpers of toml_config.hpp

// [surface] mesh and unit.
BodyMeshFile read_mesh_and_unit(const Section& t, const std::filesystem::path& base) {
  BodyMeshFile body;
  const std::string mesh_expected = "a mesh file name (OBJ, STL, PLY or OFF)";
  body.mesh = base / text_of(t, t.required("mesh", mesh_expected), "mesh", mesh_expected);
  const std::string unit_expected = "the length of one file unit, e.g. \"mm\" or \"15.8 mm\"";
  const toml::node& unit = t.required("unit", unit_expected);
  const std::string unit_text = text_of(t, unit, "unit", unit_expected);
  body.mesh_unit = t.at(unit, [&] {
    try {
      return units::unit_factor(unit_text, Dimension::Length, t.what("unit"));
    } catch (const InvalidInput&) {
      return units::parse_quantity(unit_text, Dimension::Length, t.what("unit"));
    }
  });
  if (!(body.mesh_unit > 0)) {
    t.fail(unit, "unit", fmt::format("'{}' is not positive, expected {}", unit_text, unit_expected));
  }
  return body;
}

// A point: ["x mm", "y mm", "z mm"].
Eigen::Vector3d point_of(const Section& t, const toml::node& node, std::string_view key) {
  if (!node.is_array() || node.as_array()->size() != 3) {
    t.fail(node, key, fmt::format("{} is not a point, expected [\"x mm\", \"y mm\", \"z mm\"]", describe(node)));
  }
  Eigen::Vector3d point;
  for (int i = 0; i < 3; ++i) point[i] = quantity_of(t, *node.as_array()->get(i), key, Dimension::Length);
  return point;
}

void read_surface(const Section& t, const std::filesystem::path& base, PatchCase& c) {
  const BodyMeshFile body = read_mesh_and_unit(t, base);
  c.mesh = body.mesh;
  c.mesh_unit = body.mesh_unit;
  const toml::node* vertex = t.optional("center_vertex");
  const toml::node* center = t.optional("center");
  if (vertex && center) t.fail(*center, "center", "given together with center_vertex, expected one of them");
  if (!vertex && !center) {
    t.fail(t.table(), "center_vertex",
           "missing, expected center_vertex = <0-based vertex index> or center = [\"x mm\", \"y mm\", \"z mm\"]");
  }
  if (vertex) {
    c.placement.center_vertex = integer_at_least(t, *vertex, "center_vertex", 0);
  } else {
    c.placement.center = point_of(t, *center, "center");
  }
  if (const toml::node* node = t.optional("rotation")) {
    c.placement.rotation = quantity_of(t, *node, "rotation", Dimension::Angle);
  }
  if (const toml::node* node = t.optional("approach")) {
    c.placement.approach = choice_of(t, *node, "approach", patch::kApproachNames);
  }
}

// [patch]: kind and the rows of the fit's tables (patch/fit_parameters.hpp), and the design's size, needle count and
// springs, which set PatchDesignOptions' fields in pairs and threes.
void read_patch(const Section& t, PatchCase& c) {
  read_parameters(t, patch::kFitParameters, "patch", c.fit);  // kind (required)
  c.design.width_u = c.design.width_v = positive_quantity(t, "size", Dimension::Length);
  const toml::node& count = t.required("needles_per_row", "an integer >= 2");
  c.design.needles_u = c.design.needles_v = integer_at_least(t, count, "needles_per_row", 2);
  const toml::node& spring = t.required("spring_constant", expected_quantity(Dimension::Stiffness));
  if (spring.is_table()) {
    const Section springs = t.subsection(spring, "spring_constant", {"u", "v", "diagonal"});
    c.design.stiffness_u = positive_quantity(springs, "u", Dimension::Stiffness);
    c.design.stiffness_v = positive_quantity(springs, "v", Dimension::Stiffness);
    c.design.stiffness_diagonal = positive_quantity(springs, "diagonal", Dimension::Stiffness);
  } else {
    c.design.stiffness_u = c.design.stiffness_v = c.design.stiffness_diagonal =
        positive_quantity_of(t, spring, "spring_constant", Dimension::Stiffness);
  }
  if (c.fit.kind == patch::PatchKind::Flexible && !t.optional("max_spring_energy")) {
    t.fail(t.table(), "max_spring_energy",
           fmt::format("missing for a flexible patch, expected {}", expected_quantity(Dimension::Energy)));
  }
  read_parameters(t, patch::kFlexibleFitParameters, "patch", c.fit.flexible);
  read_parameters(t, patch::kEquilibriumFitParameters, "patch", c.fit.equilibrium);
  c.load_given = t.optional("load") != nullptr;
  // Keys of one kind of patch given for another: an error rather than silently ignored.
  const auto only_for = [&](patch::PatchKind kind, const std::vector<std::string_view>& keys) {
    if (c.fit.kind == kind) return;
    for (std::string_view key : keys) {
      if (const toml::node* node = t.optional(key)) {
        t.fail(*node, key,
               fmt::format("applies only to kind = \"{}\", but kind = \"{}\"; remove it", patch::to_string(kind),
                           patch::to_string(c.fit.kind)));
      }
    }
  };
  only_for(patch::PatchKind::Flexible, keys_of_group(patch::kFlexibleFitParameters, "patch"));
  only_for(patch::PatchKind::Equilibrium, keys_of_group(patch::kEquilibriumFitParameters, "patch"));
}

// [patch]'s keys in the order the messages have always listed them.
std::vector<std::string_view> patch_keys() {
  std::vector<std::string_view> keys = keys_of_group(patch::kFitParameters, "patch");
  keys.insert(keys.end(), {"size", "needles_per_row", "spring_constant"});
  for (const std::vector<std::string_view>& rows : {keys_of_group(patch::kFlexibleFitParameters, "patch"),
                                                    keys_of_group(patch::kEquilibriumFitParameters, "patch")}) {
    keys.insert(keys.end(), rows.begin(), rows.end());
  }
  return keys;
}

}  // namespace

PatchCase parse_patch_case_toml(std::string_view text, std::string_view source_name,
                                const std::filesystem::path& base_folder, bool uncertainty_tables) {
  const std::string file(source_name);
  return config::patch_case_of_table(parse_toml(text, file), file, base_folder, uncertainty_tables);
}

PatchCase config::patch_case_of_table(const toml::table& root, const std::string& file,
                                      const std::filesystem::path& base_folder, bool uncertainty_tables) {
  // [needle], [tissue], [insertion] as in design files; this also rejects unknown tables.
  const DesignFile needle =
      uncertainty_tables
          ? design_of_tables(root, file, {"surface", "patch", "uncertain", "sampling", "correlation"}, false)
          : design_of_tables(root, file, {"surface", "patch"}, false);
  std::vector<std::string_view> tables{"surface", "patch", "needle", "tissue", "insertion"};
  if (uncertainty_tables) tables.insert(tables.end(), {"uncertain", "sampling", "correlation"});
  const Section top(root, "", file, tables);
  PatchCase c;
  read_surface(top.required_subsection("surface", {"mesh", "unit", "center_vertex", "center", "rotation", "approach"}),
               base_folder, c);
  read_patch(top.subsection(top.required("patch", "a table [patch]"), "patch", patch_keys()), c);
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

BodyMeshFile config::body_mesh_of_table(const toml::table& root, const std::string& file,
                                       const std::filesystem::path& base_folder) {
  const Section top(root, "", file, {"surface"});
  return read_mesh_and_unit(top.required_subsection("surface", {"mesh", "unit"}), base_folder);
}

BodyPick config::body_pick_of_table(const toml::table& root, const std::string& file,
                                   const std::filesystem::path& base_folder) {
  const Section top(root, "", file, {"surface", "ray"});
  BodyPick pick;
  pick.body = read_mesh_and_unit(top.required_subsection("surface", {"mesh", "unit"}), base_folder);
  const Section ray = top.required_subsection("ray", {"origin", "direction"});
  pick.origin = point_of(ray, ray.required("origin", "a point [\"x m\", \"y m\", \"z m\"]"), "origin");
  const std::string direction_expected = "a non-zero vector of three numbers [dx, dy, dz]";
  const toml::node& direction = ray.required("direction", direction_expected);
  const toml::array* components = direction.as_array();
  if (!components || components->size() != 3) {
    ray.fail(direction, "direction", fmt::format("{} is not a vector, expected {}", describe(direction), direction_expected));
  }
  for (int i = 0; i < 3; ++i) {
    const std::optional<double> value = components->get(static_cast<std::size_t>(i))->value<double>();
    if (!value || !std::isfinite(*value)) {
      ray.fail(direction, "direction", fmt::format("component {} is not a finite number, expected {}", i + 1,
                                                   direction_expected));
    }
    pick.direction[i] = *value;
  }
  if (!(pick.direction.norm() > 0)) ray.fail(direction, "direction", "is zero, expected " + direction_expected);
  return pick;
}

PatchCase read_patch_case(const std::filesystem::path& path) {
  return parse_patch_case_toml(read_text(path), path.string(), path.parent_path());
}

}  // namespace needlekit::io
