#include "needlekit/io/uncertainty_config.hpp"

#include "config_tables.hpp"
#include "needlekit/io/toml_config.hpp"
#include "uncertainty_tables.hpp"

namespace needlekit::io {

UncertaintyFile parse_uncertainty_toml(std::string_view text, std::string_view source_name) {
  const std::string file(source_name);
  return config::uncertainty_of_table(config::parse_toml(text, file), file);
}

UncertaintyFile config::uncertainty_of_table(const toml::table& root, const std::string& file) {
  const DesignFile design = config::design_of_tables(root, file, {"uncertain", "sampling", "correlation"}, true);
  config::UncertaintyTables tables = config::read_uncertainty_tables(root, file);
  UncertaintyFile result{{design.design, design.conditions, design.options}, std::move(tables.inputs),
                         std::move(tables.correlations), tables.sampling};
  // Resolve the keys against this design now, so that a key the design lacks or a non-physical spread is bad
  // input before anything runs.
  std::vector<std::string> notes;
  try {
    uncertainty::design_input_transform(result.design, result.inputs, result.correlations, notes);
  } catch (const InvalidInput& error) {
    config::rethrow_at_input(error, root, file, result.inputs);
  }
  return result;
}

UncertaintyFileKind uncertainty_file_kind(const std::filesystem::path& path) {
  const toml::table root = config::parse_toml(config::read_text(path), path.string());
  if (root.contains("surface")) return UncertaintyFileKind::Patch;
  return root.contains("case") ? UncertaintyFileKind::FeCase : UncertaintyFileKind::Design;
}

UncertaintyFile read_uncertainty_file(const std::filesystem::path& path) {
  return parse_uncertainty_toml(config::read_text(path), path.string());
}

}  // namespace needlekit::io
