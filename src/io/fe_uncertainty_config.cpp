#include "needlekit/io/fe_uncertainty_config.hpp"

#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/toml_config.hpp"
#include "needlekit/io/toml_parameters.hpp"
#include "needlekit/uncertainty/fe_surrogate_parameters.hpp"
#include "uncertainty_tables.hpp"

namespace needlekit::io {

FeUncertaintyFile parse_fe_uncertainty_toml(std::string_view text, std::string_view source_name,
                                            const std::filesystem::path& base_folder) {
  using namespace config;
  const std::string file(source_name);
  const toml::table root = parse_toml(text, file);
  const Section top(root, "", file, {"case", "uncertain", "sampling", "correlation", "surrogate"});
  FeUncertaintyFile result;
  const std::string expected = "an indentation case file (`needlekit indent --help`)";
  result.case_path = base_folder / text_of(top, top.required("case", expected), "case", expected);
  result.indentation = read_indentation_case(result.case_path);
  const insertion::IndentationCase& c = result.indentation;
  UncertaintyTables tables = read_uncertainty_tables(root, file, [&c](std::string_view key, std::string_view what) {
    uncertainty::fe_input_from_key(key, c, what);
    return units::Dimension::Pressure;
  });
  result.inputs = std::move(tables.inputs);
  result.correlations = std::move(tables.correlations);
  result.options.sampling = tables.sampling;
  if (const toml::node* node = root.get("surrogate")) {
    if (!node->is_table()) top.fail(*node, "surrogate", "expected a table [surrogate]");
    const Section s(*node->as_table(), "surrogate", file,
                    keys_of_group(uncertainty::kFeSurrogateParameters, "surrogate"));
    read_parameters(s, uncertainty::kFeSurrogateParameters, "surrogate", result.options);
  }
  std::vector<std::string> notes;
  try {
    uncertainty::fe_input_transform(c, result.inputs, result.correlations, notes);
  } catch (const InvalidInput& error) {
    rethrow_at_input(error, root, file, result.inputs);
  }
  return result;
}

FeUncertaintyFile read_fe_uncertainty_file(const std::filesystem::path& path) {
  return parse_fe_uncertainty_toml(config::read_text(path), path.string(), path.parent_path());
}

}  // namespace needlekit::io
