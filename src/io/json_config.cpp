#include "needlekit/io/json_config.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "config_tables.hpp"
#include "needlekit/core/errors.hpp"

namespace needlekit::io {
namespace {

using Json = nlohmann::ordered_json;  // keeps the body's key order

std::string child_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

// toml++ keeps a table's keys sorted; readers that need the file's order (the [uncertain] inputs) restore it from the
// keys' positions. A JSON key gets line 1 and its rank in the body as its column.
struct Converter {
  std::string file;
  toml::source_index rank = 0;

  toml::key key_of(std::string_view name) {
    ++rank;
    return toml::key(name, toml::source_region{{1, rank}, {1, rank}, nullptr});
  }

  toml::table table_of(const Json& object, const std::string& path) {
    toml::table table;
    for (const auto& [name, value] : object.items()) {
      toml::key key = key_of(name);
      insert_converted(value, child_path(path, name),
                       [&table, &key](toml::node&& node) { table.insert(std::move(key), std::move(node)); });
    }
    return table;
  }

  // What the TOML reader would see for `value`; `path` is its dotted key for messages.
  void insert_converted(const Json& value, const std::string& path, const std::function<void(toml::node&&)>& insert) {
    using Type = Json::value_t;
    switch (value.type()) {
      case Type::object: {
        toml::table table = table_of(value, path);
        insert(std::move(table));
        return;
      }
      case Type::array: {
        toml::array array;
        for (const Json& element : value) {
          insert_converted(element, path, [&array](toml::node&& node) { array.push_back(std::move(node)); });
        }
        insert(std::move(array));
        return;
      }
      case Type::string: insert(toml::value<std::string>(value.get<std::string>())); return;
      case Type::boolean: insert(toml::value<bool>(value.get<bool>())); return;
      case Type::number_integer: insert(toml::value<std::int64_t>(value.get<std::int64_t>())); return;
      case Type::number_unsigned:
        if (value.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
          throw InvalidInput(fmt::format("{}:1: key '{}': {} is out of range, expected an integer below 2^63", file,
                                         path, value.get<std::uint64_t>()));
        }
        insert(toml::value<std::int64_t>(value.get<std::int64_t>()));
        return;
      case Type::number_float: insert(toml::value<double>(value.get<double>())); return;
      default:
        throw InvalidInput(fmt::format("{}:1: key '{}': null is not a value, expected the key's value or no key", file,
                                       path.empty() ? "(top level)" : path));
    }
  }
};

toml::table root_of(std::string_view text, const std::string& file) {
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::parse_error& error) {
    throw IoError(fmt::format("{}:1: invalid JSON: {}", file, error.what()));
  }
  if (!json.is_object()) {
    throw IoError(fmt::format("{}:1: invalid design: the JSON is {}, expected an object of tables (e.g. "
                              "{{\"needle\": {{...}}}})",
                              file, json.type_name()));
  }
  return Converter{file}.table_of(json, "");
}

}  // namespace

DesignFile parse_design_json(std::string_view text, std::string_view source_name) {
  const std::string file(source_name);
  return config::design_of_table(root_of(text, file), file);
}

SpaceFile parse_space_json(std::string_view text, std::string_view source_name) {
  const std::string file(source_name);
  return config::space_of_table(root_of(text, file), file);
}

UncertaintyFile parse_uncertainty_json(std::string_view text, std::string_view source_name) {
  const std::string file(source_name);
  return config::uncertainty_of_table(root_of(text, file), file);
}

namespace {

// The folder of the mesh that root's surface.mesh names, a key of `meshes`; InvalidInput naming surface.mesh and the
// names offered for any other string. Empty when surface.mesh is missing or not a string (the reader says so).
std::filesystem::path offered_mesh_folder(const toml::table& root, const std::string& file,
                                          const std::map<std::string, std::filesystem::path>& meshes) {
  const toml::node* mesh = root.at_path("surface.mesh").node();
  if (!mesh || !mesh->is_string()) return {};
  const auto found = meshes.find(mesh->as_string()->get());
  if (found == meshes.end() || found->second.filename() != found->first) {
    std::vector<std::string_view> names;
    for (const auto& [name, path] : meshes) names.push_back(name);
    throw InvalidInput(fmt::format("{}:1: key 'surface.mesh': '{}' is not one of the meshes offered, expected one "
                                   "of: {}",
                                   file, mesh->as_string()->get(), fmt::join(names, ", ")));
  }
  return found->second.parent_path();
}

}  // namespace

PatchCase parse_patch_case_json(std::string_view text, std::string_view source_name,
                                const std::map<std::string, std::filesystem::path>& meshes) {
  const std::string file(source_name);
  const toml::table root = root_of(text, file);
  return config::patch_case_of_table(root, file, offered_mesh_folder(root, file, meshes), false);
}

BodyMeshFile parse_body_mesh_json(std::string_view text, std::string_view source_name,
                                  const std::map<std::string, std::filesystem::path>& meshes) {
  const std::string file(source_name);
  const toml::table root = root_of(text, file);
  return config::body_mesh_of_table(root, file, offered_mesh_folder(root, file, meshes));
}

BodyPick parse_body_pick_json(std::string_view text, std::string_view source_name,
                              const std::map<std::string, std::filesystem::path>& meshes) {
  const std::string file(source_name);
  const toml::table root = root_of(text, file);
  return config::body_pick_of_table(root, file, offered_mesh_folder(root, file, meshes));
}

}  // namespace needlekit::io
