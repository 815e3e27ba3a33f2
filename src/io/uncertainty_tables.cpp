#include "uncertainty_tables.hpp"

#include "needlekit/io/toml_config.hpp"
#include "needlekit/io/toml_parameters.hpp"
#include "needlekit/uncertainty/propagation_parameters.hpp"

namespace needlekit::io::config {
namespace {

using uncertainty::DistributionKind;

constexpr std::string_view kLeafKeys[] = {"distribution", "mean", "sd", "median", "sigma_log", "min", "max", "mode"};

// The parameters each distribution takes (the others are errors) and which of them are required.
struct Parameters {
  std::vector<std::string_view> allowed, required;
};
Parameters parameters_of(DistributionKind kind) {
  switch (kind) {
    case DistributionKind::Normal: return {{"mean", "sd"}, {"sd"}};
    case DistributionKind::TruncatedNormal: return {{"mean", "sd", "min", "max"}, {"sd", "min", "max"}};
    case DistributionKind::Lognormal: return {{"median", "sigma_log"}, {"sigma_log"}};
    case DistributionKind::Uniform: return {{"min", "max"}, {"min", "max"}};
    case DistributionKind::Triangular: return {{"min", "max", "mode"}, {"min", "max"}};
  }
  return {};
}

uncertainty::DesignUncertainInput uncertain_input(const toml::table& table, const std::string& key,
                                                  std::string_view file, const InputDimension& dimension_of) {
  const std::string path = fmt::format("uncertain.\"{}\"", key);
  const Section section(table, path, file,
                        {"distribution", "mean", "sd", "median", "sigma_log", "min", "max", "mode"});
  const std::string expected = "one of: " + choices_of(uncertainty::kDistributionKindNames);
  const toml::node& kind_node = section.required("distribution", expected);
  const std::string kind_text = text_of(section, kind_node, "distribution", expected);
  uncertainty::DesignUncertainInput input;
  input.key = key;
  input.distribution.kind =
      section.at(kind_node, [&] { return uncertainty::distribution_kind_from_string(kind_text, section.what("distribution")); });

  const units::Dimension dimension = section.at(table, [&] { return dimension_of(key, fmt::format("key '{}'", path)); });
  const Parameters parameters = parameters_of(input.distribution.kind);
  for (std::string_view name : kLeafKeys) {
    if (name == "distribution" || !section.optional(name)) continue;
    if (std::find(parameters.allowed.begin(), parameters.allowed.end(), name) == parameters.allowed.end()) {
      section.fail(*section.optional(name), name,
                   fmt::format("does not apply to a {} distribution, expected only: {}", kind_text,
                               fmt::join(parameters.allowed, ", ")));
    }
  }
  for (std::string_view name : parameters.required) {
    section.required(name, name == "sigma_log" ? "a number >= 0" : expected_quantity(dimension));
  }
  const auto value = [&](std::string_view name) { return quantity_of(section, *section.optional(name), name, dimension); };
  uncertainty::Distribution& d = input.distribution;
  const bool has_centre = section.optional("mean") || section.optional("median") || section.optional("mode");
  if (section.optional("mean")) d.mean = value("mean");
  if (section.optional("sd")) d.sd = value("sd");
  if (section.optional("median")) d.median = value("median");
  if (section.optional("sigma_log")) {
    const toml::node& node = *section.optional("sigma_log");
    if (!node.is_number()) section.fail(node, "sigma_log", fmt::format("{} is not a number, expected a number >= 0 (the sd of ln x, no unit)", describe(node)));
    d.sigma_log = *node.value<double>();
  }
  if (section.optional("min")) d.min = value("min");
  if (section.optional("max")) d.max = value("max");
  if (section.optional("mode")) d.mode = value("mode");
  if (d.kind == DistributionKind::Triangular) {
    if (!section.optional("mode")) d.mode = 0.5 * (d.min + d.max);
  } else {
    input.centred_on_nominal = !has_centre && d.kind != DistributionKind::Uniform;
  }
  section.at(table, [&] {
    uncertainty::Distribution check = d;
    if (input.centred_on_nominal) check.mean = check.median = 1;  // a placeholder: the nominal comes later
    uncertainty::validate(check, fmt::format("key '{}'", path));
    return 0;
  });
  return input;
}

// An input with where it was written (toml++ keeps keys sorted; the file's order is restored from the positions).
struct PlacedInput {
  toml::source_position at;
  uncertainty::DesignUncertainInput input;
};

// [uncertain] entries: inline tables with a `distribution`; dotted keys written bare (needle.tip_diameter = {...})
// arrive as nested tables and are flattened back to their dotted key.
void collect_inputs(const toml::table& table, const std::string& prefix, std::string_view file,
                    const InputDimension& dimension_of, std::vector<PlacedInput>& inputs) {
  for (auto&& [key, node] : table) {
    const std::string name = prefix.empty() ? std::string(key.str()) : fmt::format("{}.{}", prefix, key.str());
    if (!node.is_table()) {
      throw InvalidInput(fmt::format("{} key 'uncertain.\"{}\"': {} is not a distribution, expected an inline table "
                                     "{{ distribution = \"normal\", mean = ..., sd = ... }}",
                                     location(file, node.source()), name, describe(node)));
    }
    const toml::table& child = *node.as_table();
    if (child.contains("distribution")) {
      inputs.push_back({key.source().begin, uncertain_input(child, name, file, dimension_of)});
    } else {
      collect_inputs(child, name, file, dimension_of, inputs);
    }
  }
}

}  // namespace

units::Dimension design_input_dimension(std::string_view key, std::string_view what) {
  return uncertainty::info(uncertainty::design_input_from_key(key, what)).dimension;
}

UncertaintyTables read_uncertainty_tables(const toml::table& root, std::string_view file,
                                          const InputDimension& dimension_of) {
  UncertaintyTables tables;
  const toml::node* uncertain = root.get("uncertain");
  if (!uncertain || !uncertain->is_table() || uncertain->as_table()->empty()) {
    throw InvalidInput(fmt::format("{} table [uncertain]: missing or empty, expected at least one uncertain input "
                                   "such as \"tissue.alpha\" = {{ distribution = \"lognormal\", sigma_log = 0.2 }}",
                                   location(file, uncertain ? uncertain->source() : root.source())));
  }
  std::vector<PlacedInput> placed;
  collect_inputs(*uncertain->as_table(), "", file, dimension_of, placed);
  std::sort(placed.begin(), placed.end(), [](const PlacedInput& a, const PlacedInput& b) {
    return a.at.line != b.at.line ? a.at.line < b.at.line : a.at.column < b.at.column;
  });
  for (PlacedInput& p : placed) tables.inputs.push_back(std::move(p.input));
  if (const toml::node* node = root.get("sampling")) {
    const Section sampling(*node->as_table(), "sampling", file,
                           keys_of_group(uncertainty::kPropagationParameters, "sampling"));
    read_parameters(sampling, uncertainty::kPropagationParameters, "sampling", tables.sampling);
  }
  if (const toml::node* node = root.get("correlation")) {
    if (!node->is_array_of_tables()) {
      throw InvalidInput(fmt::format("{} key 'correlation': expected [[correlation]] tables with inputs = [\"a\", "
                                     "\"b\"] and rho",
                                     location(file, node->source())));
    }
    for (const toml::node& entry : *node->as_array()) {
      const Section c(*entry.as_table(), "correlation", file, {"inputs", "rho"});
      const toml::node& pair = c.required("inputs", "two uncertain keys [\"a\", \"b\"]");
      if (!pair.is_array() || pair.as_array()->size() != 2 || !pair.as_array()->get(0)->is_string() ||
          !pair.as_array()->get(1)->is_string()) {
        c.fail(pair, "inputs", "expected two uncertain keys [\"a\", \"b\"]");
      }
      uncertainty::Correlation correlation;
      for (int side = 0; side < 2; ++side) {
        const std::string key = pair.as_array()->get(static_cast<std::size_t>(side))->as_string()->get();
        const auto found = std::find_if(tables.inputs.begin(), tables.inputs.end(),
                                        [&](const auto& input) { return input.key == key; });
        if (found == tables.inputs.end()) {
          c.fail(pair, "inputs", fmt::format("'{}' is not in [uncertain], expected keys of uncertain inputs", key));
        }
        (side == 0 ? correlation.first : correlation.second) = static_cast<std::size_t>(found - tables.inputs.begin());
      }
      const toml::node& rho = c.required("rho", "a number in (-1, 1)");
      if (!rho.is_number() || !(*rho.value<double>() > -1 && *rho.value<double>() < 1)) {
        c.fail(rho, "rho", fmt::format("{} is not a number in (-1, 1)", describe(rho)));
      }
      correlation.rho = *rho.value<double>();
      tables.correlations.push_back(correlation);
    }
  }
  return tables;
}

void rethrow_at_input(const InvalidInput& error, const toml::table& root, std::string_view file,
                      const std::vector<uncertainty::DesignUncertainInput>& inputs) {
  const std::string_view message = error.what();
  const toml::node& uncertain = *root.get("uncertain");
  const toml::node* at = &uncertain;
  for (const auto& input : inputs) {
    if (message.find(fmt::format("\"{}\"", input.key)) != std::string_view::npos) {
      if (const toml::node* node = uncertain.as_table()->get(input.key)) at = node;
    }
  }
  throw InvalidInput(fmt::format("{} {}", location(file, at->source()), message));
}

}  // namespace needlekit::io::config
