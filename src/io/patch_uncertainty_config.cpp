#include "needlekit/io/patch_uncertainty_config.hpp"

#include "needlekit/io/toml_config.hpp"
#include "uncertainty_tables.hpp"

namespace needlekit::io {
namespace {
units::Dimension patch_input_dimension(std::string_view key, std::string_view what) {
  return uncertainty::patch_input_from_key(key, what).dimension;
}
}  // namespace

patch::FitAndEvaluateOptions fit_and_evaluate_options(const PatchCase& c) {
  return {c.placement, c.fit, c.evaluation, false, nullptr};
}

PatchUncertaintyFile parse_patch_uncertainty_toml(std::string_view text, std::string_view source_name,
                                                  const std::filesystem::path& base_folder) {
  const std::string file(source_name);
  PatchUncertaintyFile result;
  result.patch = parse_patch_case_toml(text, file, base_folder, true);
  const toml::table root = config::parse_toml(text, file);
  config::UncertaintyTables tables = config::read_uncertainty_tables(root, file, patch_input_dimension);
  result.inputs = std::move(tables.inputs);
  result.correlations = std::move(tables.correlations);
  result.sampling = tables.sampling;
  // Resolve the keys against this case now (a bore on a solid needle, a non-physical spread): bad input before
  // anything runs.
  std::vector<std::string> notes;
  try {
    uncertainty::patch_input_transform(result.patch.design, fit_and_evaluate_options(result.patch), result.inputs,
                                       result.correlations, notes);
  } catch (const InvalidInput& error) {
    config::rethrow_at_input(error, root, file, result.inputs);
  }
  return result;
}

PatchUncertaintyFile read_patch_uncertainty_file(const std::filesystem::path& path) {
  return parse_patch_uncertainty_toml(config::read_text(path), path.string(), path.parent_path());
}

}  // namespace needlekit::io
