#include "needlekit/io/tissue_config.hpp"

#include <chrono>
#include <limits>

#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/layered_block_parameters.hpp"
#include "needlekit/mesh/msh_import.hpp"
#include "tissue_config_toml.hpp"
#include "needlekit/io/toml_parameters.hpp"

namespace needlekit::io {
namespace config {
namespace {

constexpr double kDefaultHeight = 1150e-6;  // dissertation §3.3.2 / §6.2 block

double poisson_ratio_of(const Section& section, const toml::node& node) {
  const double nu = number_at_least(section, node, "poisson_ratio", -1.0);
  if (!(nu > -1 && nu < 0.5)) {
    section.fail(node, "poisson_ratio", fmt::format("{} is out of range, expected a number in (-1, 0.5)", nu));
  }
  return nu;
}

struct LayerEntry {
  mesh::TissueLayer layer;
  const toml::node* thickness = nullptr;
  bool rest = false;
};

std::vector<mesh::TissueLayer> layers_of(const Section& tissue, const toml::node& node, std::optional<double> height,
                                         const toml::node* height_node) {
  const std::string expected = "an array of tables [[tissue.layers]] with name, thickness, youngs_modulus, "
                               "poisson_ratio";
  if (!node.is_array() || node.as_array()->empty()) {
    tissue.fail(node, "layers", fmt::format("{} is not a non-empty array of layers, expected {}", describe(node),
                                            expected));
  }
  const toml::array& array = *node.as_array();
  std::vector<LayerEntry> entries;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string key = fmt::format("layers[{}]", i);
    const Section layer = tissue.subsection(*array.get(i), key, {"name", "thickness", "youngs_modulus", "poisson_ratio"});
    LayerEntry entry;
    entry.layer.name = text_of(layer, layer.required("name", "a name, e.g. \"dermis\""), "name", "a name");
    if (entry.layer.name.empty()) layer.fail(*layer.optional("name"), "name", "empty, expected a layer name");
    for (const LayerEntry& before : entries) {
      if (before.layer.name == entry.layer.name) {
        layer.fail(*layer.optional("name"), "name",
                   fmt::format("\"{}\" names two layers, expected unique names", entry.layer.name));
      }
    }
    entry.thickness = &layer.required("thickness", "a length such as \"140 um\", or \"rest\" for the last layer");
    if (entry.thickness->is_string() && entry.thickness->as_string()->get() == "rest") {
      if (i + 1 != array.size()) {
        layer.fail(*entry.thickness, "thickness", "\"rest\" is allowed only for the last layer, expected a length");
      }
      entry.rest = true;
    } else {
      entry.layer.thickness = positive_quantity_of(layer, *entry.thickness, "thickness", Dimension::Length);
    }
    entry.layer.youngs_modulus = positive_quantity(layer, "youngs_modulus", Dimension::Pressure);
    if (const toml::node* nu = layer.optional("poisson_ratio")) entry.layer.poisson_ratio = poisson_ratio_of(layer, *nu);
    entries.push_back(entry);
  }
  double others = 0;
  for (const LayerEntry& e : entries) others += e.layer.thickness;
  if (entries.back().rest) {
    const double total = height.value_or(kDefaultHeight);
    if (!(total - others > 1e-9 * total)) {
      tissue.fail(*entries.back().thickness, fmt::format("layers[{}].thickness", entries.size() - 1),
                  fmt::format("\"rest\" of a {:g} um block below {:g} um of layers is not positive, expected the layers "
                              "above to be thinner than the block",
                              total * 1e6, others * 1e6));
    }
    entries.back().layer.thickness = total - others;
  } else if (height && std::abs(*height - others) > 1e-9 * *height) {
    tissue.fail(*height_node, "height",
                fmt::format("{:g} um differs from the {:g} um sum of the layer thicknesses, expected them to be equal (or "
                            "the last thickness = \"rest\")",
                            *height * 1e6, others * 1e6));
  }
  std::vector<mesh::TissueLayer> layers;
  for (const LayerEntry& e : entries) layers.push_back(e.layer);
  return layers;
}

std::vector<Eigen::Vector2d> sites_of(const Section& section, const toml::node& node) {
  const std::string expected = "an array of [x, y] lengths, e.g. [[\"-800 um\", \"0 um\"], [\"800 um\", \"0 um\"]]";
  if (!node.is_array() || node.as_array()->empty()) {
    section.fail(node, "sites", fmt::format("{} is not a non-empty array, expected {}", describe(node), expected));
  }
  std::vector<Eigen::Vector2d> sites;
  for (std::size_t i = 0; i < node.as_array()->size(); ++i) {
    const toml::node& pair = *node.as_array()->get(i);
    const std::string key = fmt::format("sites[{}]", i);
    if (!pair.is_array() || pair.as_array()->size() != 2) {
      section.fail(pair, key, fmt::format("{} is not an [x, y] pair, expected {}", describe(pair), expected));
    }
    sites.emplace_back(quantity_of(section, *pair.as_array()->get(0), key + ".x", Dimension::Length),
                       quantity_of(section, *pair.as_array()->get(1), key + ".y", Dimension::Length));
  }
  return sites;
}

// The keys of the rows of mesh::kLayeredBlockParameters in `group`, then `others`.
std::vector<std::string_view> keys_with(std::string_view group, std::initializer_list<std::string_view> others) {
  std::vector<std::string_view> keys = keys_of_group(mesh::kLayeredBlockParameters, group);
  keys.insert(keys.end(), others);
  return keys;
}

// The top-level table `key` (other top-level keys belong to other readers and are not checked here).
Section table_of(const toml::node& node, std::string_view key, std::string_view file,
                 const std::vector<std::string_view>& allowed_keys) {
  if (!node.is_table()) {
    throw InvalidInput(fmt::format("{} key '{}': {} is not a table, expected a table [{}] with keys {}",
                                   location(file, node.source()), key, describe(node), key,
                                   fmt::join(allowed_keys, ", ")));
  }
  return Section(*node.as_table(), std::string(key), file, allowed_keys);
}

// [tissue]: the block's width and length, and its layers from a preset (the last layer taking the rest of a given
// height) or from [[tissue.layers]].
void read_tissue_table(const toml::node& node, std::string_view file, mesh::LayeredBlockOptions& o) {
  const Section tissue = table_of(node, "tissue", file, keys_with("tissue", {"height", "preset", "layers"}));
  read_parameters(tissue, mesh::kLayeredBlockParameters, "tissue", o);  // width, length
  const std::optional<double> height = optional_positive_quantity(tissue, "height", Dimension::Length);
  const toml::node* preset = tissue.optional("preset");
  const toml::node* layers = tissue.optional("layers");
  if (preset && layers) tissue.fail(*layers, "layers", "given together with preset, expected one of preset or layers");
  if (preset) {
    const std::string name = text_of(tissue, *preset, "preset", "a tissue preset name");
    o.layers = tissue.at(*preset, [&] { return materials::tissue_preset(name, tissue.what("preset")).layers; });
    if (height) {  // the preset's last layer takes the rest of the given height
      double others = 0;
      for (std::size_t i = 0; i + 1 < o.layers.size(); ++i) others += o.layers[i].thickness;
      if (!(*height > others)) {
        tissue.fail(*tissue.optional("height"), "height",
                    fmt::format("{:g} um leaves no room for the preset's last layer below {:g} um, expected more",
                                *height * 1e6, others * 1e6));
      }
      o.layers.back().thickness = *height - others;
    }
  } else if (layers) {
    o.layers = layers_of(tissue, *layers, height, tissue.optional("height"));
  } else if (height) {
    o.layers.back().thickness = *height - 160e-6;
    if (!(o.layers.back().thickness > 0)) {
      tissue.fail(*tissue.optional("height"), "height", "is not deeper than the 160 um epidermis, expected more");
    }
  }
}

// [mesh]: a .msh file (with its unit), or the block's mesh sizes, sites and limits.
void read_mesh_table(const toml::node& node, std::string_view file, const std::filesystem::path& base_dir,
                     TissueCase& tissue) {
  mesh::LayeredBlockOptions& o = tissue.block;
  const Section m = table_of(node, "mesh", file, keys_with("mesh", {"sites", "file", "unit"}));
  if (const toml::node* f = m.optional("file")) {
    const std::string path = text_of(m, *f, "file", "a .msh file name");
    if (path.empty()) m.fail(*f, "file", "empty, expected a .msh file name");
    tissue.msh_file = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : base_dir / path;
    for (std::string_view key : keys_with("mesh", {"sites"})) {
      if (const toml::node* other = m.optional(key)) {
        m.fail(*other, key, "given together with file, expected either a mesh file or the block's mesh sizes");
      }
    }
  }
  if (const toml::node* u = m.optional("unit")) {
    if (tissue.msh_file.empty()) m.fail(*u, "unit", "given without file, expected it only with a mesh file");
    const std::string unit = text_of(m, *u, "unit", "a length unit such as \"um\" or \"mm\"");
    tissue.msh_unit = m.at(*u, [&] { return units::unit_factor(unit, Dimension::Length, m.what("unit")); });
  }
  read_parameters(m, mesh::kLayeredBlockParameters, "mesh", o);  // sizes, split, limits
  if (const toml::node* s = m.optional("sites")) o.insertion_sites = sites_of(m, *s);
  if (o.size_far < o.size_at_site) {
    m.fail(m.optional("size_far") ? *m.optional("size_far") : node, "size_far",
           fmt::format("{:g} um is smaller than size_at_tip = {:g} um, expected size_far >= size_at_tip",
                       o.size_far * 1e6, o.size_at_site * 1e6));
  }
  for (std::size_t i = 0; tissue.msh_file.empty() && i < o.insertion_sites.size(); ++i) {
    const Eigen::Vector2d& p = o.insertion_sites[i];
    if (!(std::abs(p.x()) < 0.5 * o.width && std::abs(p.y()) < 0.5 * o.length)) {
      m.fail(*m.optional("sites"), fmt::format("sites[{}]", i),
             fmt::format("({:g}, {:g}) um is not inside the {:g} x {:g} um top surface centred on (0, 0), expected |x| < "
                         "width/2 and |y| < length/2",
                         p.x() * 1e6, p.y() * 1e6, o.width * 1e6, o.length * 1e6));
    }
  }
}

}  // namespace

TissueCase tissue_case_of(const toml::table& root, std::string_view file, const std::filesystem::path& base_dir) {
  TissueCase tissue;
  mesh::LayeredBlockOptions& o = tissue.block;
  o.layers = materials::skin_layers();
  if (!root.get("tissue")) {  // an empty file would mesh the default block without a word
    throw InvalidInput(fmt::format("{}:1: missing table [tissue], expected a table [tissue] with preset = \"{}\" "
                                   "(or another of: {}) or [[tissue.layers]]",
                                   file, materials::tissue_preset_names().front(),
                                   fmt::join(materials::tissue_preset_names(), ", ")));
  }
  if (const toml::node* node = root.get("tissue")) read_tissue_table(*node, file, o);
  if (const toml::node* node = root.get("mesh")) read_mesh_table(*node, file, base_dir, tissue);
  return tissue;
}

}  // namespace config

TissueCase parse_tissue_case_toml(std::string_view text, std::string_view source_name,
                                  const std::filesystem::path& base_dir) {
  const toml::table root = config::parse_toml(text, source_name);
  TissueCase tissue = config::tissue_case_of(root, source_name, base_dir);
  if (const toml::node* array = root.get("array")) {
    tissue.warnings.push_back(fmt::format(
        "{} table [array]: not read here; this meshes the block of [tissue] and [mesh] around the insertion sites "
        "of [mesh] (one, centred, by default), not the array's block (`needlekit indent` meshes that: its "
        "NAME_step_001.vtu holds the mesh)",
        config::location(source_name, array->source())));
  }
  return tissue;
}

TissueCase read_tissue_case(const std::filesystem::path& path) {
  const std::string name = path.string();
  return parse_tissue_case_toml(config::read_text(path), name, path.parent_path());
}

mesh::LayeredBlockOptions parse_tissue_block_toml(std::string_view text, std::string_view source_name) {
  TissueCase tissue = parse_tissue_case_toml(text, source_name);
  if (!tissue.msh_file.empty()) {
    throw InvalidInput(fmt::format("{}: [mesh] names a mesh file, expected a parametric block", source_name));
  }
  return tissue.block;
}

mesh::LayeredBlockOptions read_tissue_block(const std::filesystem::path& path) {
  const std::string name = path.string();
  return parse_tissue_block_toml(config::read_text(path), name);
}

mesh::LayeredBlockResult tissue_mesh(const TissueCase& tissue) {
  if (tissue.msh_file.empty()) return mesh::layered_block_mesh(tissue.block);
  const auto start = std::chrono::steady_clock::now();
  mesh::MshImportOptions options;
  options.unit = tissue.msh_unit;
  options.layers = tissue.block.layers;
  mesh::MshImportResult imported = mesh::msh_import(tissue.msh_file, options);
  double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
  for (const auto& p : imported.mesh.nodes) top = std::max(top, p.z()), bottom = std::min(bottom, p.z());
  if (std::abs(top) > 1e-6 * (top - bottom)) {
    throw InvalidInput(fmt::format("{}: the mesh's top is at z = {:g} um; expected the tissue's top surface at z = 0 "
                                   "(the tissue below it, needles coming from z > 0)",
                                   tissue.msh_file.string(), top * 1e6));
  }
  mesh::LayeredBlockResult result;
  result.mesh = std::move(imported.mesh);
  result.quality = std::move(imported.quality);
  result.mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace needlekit::io
