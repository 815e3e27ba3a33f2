#include "needlekit/reference/parameter_reference.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <utility>
#include <vector>

#include "needlekit/calibration/calibration_solver_parameters.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/insertion/insertion_curve_parameters.hpp"
#include "needlekit/insertion/loading_parameters.hpp"
#include "needlekit/insertion/post_puncture_parameters.hpp"
#include "needlekit/insertion/puncture_parameters.hpp"
#include "needlekit/insertion/triangle_classification_parameters.hpp"
#include "needlekit/mesh/layered_block_parameters.hpp"
#include "needlekit/patch/fit_parameters.hpp"
#include "needlekit/patch/patch_design_parameters.hpp"
#include "needlekit/uncertainty/fe_surrogate_parameters.hpp"
#include "needlekit/uncertainty/propagation_parameters.hpp"
#include "needlekit/io/indentation_case.hpp"

namespace needlekit::reference {
namespace {

std::string escaped_for_table(std::string text) {
  std::string escaped;
  for (char c : text) {
    if (c == '|') escaped += '\\';
    escaped += c;
  }
  return escaped;
}

std::string description_of(const ParameterText& parameter, std::string_view options) {
  std::string text = fmt::format("{}\n  {}\n", parameter.key, parameter.meaning);
  text += fmt::format("  kind:    {}\n", parameter.kind);
  text += fmt::format("  unit:    {}\n", parameter.unit.empty() ? "none" : parameter.unit);
  text += fmt::format("  default: {}\n", parameter.required   ? fmt::format("required in files ({} in Python)",
                                                                             parameter.default_text)
                                           : parameter.optional ? fmt::format("optional: not given ({} in Python)",
                                                                             parameter.default_text)
                                                                : parameter.default_text);
  text += fmt::format("  range:   {}\n", parameter.range);
  text += fmt::format("  Python:  {}.{}\n", options, parameter.name);
  if (!parameter.choices.empty()) text += "  choices:\n" + parameter.choices;
  return text;
}

}  // namespace

std::vector<ParameterGroup> parameter_reference() {
  return {
      {"indentation cases (`needlekit indent`), [model] and [solver]", "SolverOptions",
       parameter_texts(fem::kSolverParameters, io::case_solver_defaults())},
      {"indentation and insertion cases (`needlekit indent`; insert), [loading]", "IndentationCase",
       parameter_texts<insertion::Loading>(insertion::kLoadingParameters)},
      {"indentation cases, [puncture] (besides toughness_from)", "PunctureOptions",
       parameter_texts(insertion::kPunctureParameters, insertion::PunctureOptions{})},
      {"insertion cases (`needlekit insert`), [post_puncture]: the model K and S", "PostPunctureFitOptions",
       parameter_texts<insertion::PostPunctureFitOptions>(insertion::kPostPunctureFitParameters)},
      {"insertion cases (`needlekit insert`), [post_puncture]: the curve", "InsertionCurveOptions",
       parameter_texts<insertion::InsertionCurveOptions>(insertion::kInsertionCurveParameters)},
      {"insertion cases (`needlekit insert`), [post_puncture]: the beta load (besides measured, a CSV file)",
       "PostPunctureOptions",
       parameter_texts<insertion::PostPunctureOptions>(insertion::kPostPunctureParameters)},
      {"insertion cases (`needlekit insert`), [post_puncture]: the triangle classes",
       "TriangleClassificationOptions",
       parameter_texts<insertion::TriangleClassificationOptions>(insertion::kTriangleClassificationParameters)},
      {"uncertainty files (`needlekit uncertainty`, `optimize` with [uncertain]), [sampling]", "PropagationOptions",
       parameter_texts<uncertainty::PropagationOptions>(uncertainty::kPropagationParameters)},
      {"FE uncertainty files (`needlekit uncertainty` with case = \"indent.toml\"), [surrogate]", "FeSurrogateOptions",
       parameter_texts<uncertainty::FeSurrogateOptions>(uncertainty::kFeSurrogateParameters)},
      {"calibration files (`needlekit calibrate`), [solver]", "CalibrationSolverSettings",
       parameter_texts<calibration::SolverSettings>(calibration::kCalibrationSolverParameters)},
      {"tissue blocks (`needlekit tissue-mesh`; indent, insert), [tissue] and [mesh]", "LayeredBlockOptions",
       parameter_texts<mesh::LayeredBlockOptions>(mesh::kLayeredBlockParameters)},
      {"patch designs (Python; a patch case's [patch] size, needles_per_row and spring_constant set them in pairs and "
       "threes)",
       "PatchDesignOptions", parameter_texts<patch::PatchDesignOptions>(patch::kPatchDesignParameters)},
      {"patch cases (`needlekit patch`), [patch] (besides size, needles_per_row, spring_constant)", "FitOptions",
       parameter_texts<patch::FitOptions>(patch::kFitParameters)},
      {"patch cases (`needlekit patch`), [patch], kind = \"flexible\"", "FlexibleFitOptions",
       parameter_texts<patch::FlexibleFitOptions>(patch::kFlexibleFitParameters)},
      {"patch cases (`needlekit patch`), [patch], kind = \"equilibrium\"", "EquilibriumFitOptions",
       parameter_texts<patch::EquilibriumFitOptions>(patch::kEquilibriumFitParameters)},
  };
}

std::vector<std::string> parameter_keys() {
  std::vector<std::string> keys;
  for (const ParameterGroup& group : parameter_reference()) {
    for (const ParameterText& parameter : group.parameters) keys.push_back(parameter.key);
  }
  return keys;
}

std::string described(std::string_view key) {
  // A key of two kinds of file (solver.max_iterations: indentation cases and calibration files) or of two Python
  // classes (threads) is described once for each, headed by where it is written.
  std::vector<std::pair<const ParameterGroup*, const ParameterText*>> found;
  const std::vector<ParameterGroup> groups = parameter_reference();
  for (const ParameterGroup& group : groups) {
    for (const ParameterText& parameter : group.parameters) {
      if (parameter.key == key) found.emplace_back(&group, &parameter);
    }
  }
  if (found.size() == 1) return description_of(*found.front().second, found.front().first->options);
  if (!found.empty()) {
    std::string text;
    for (const auto& [group, parameter] : found) {
      text += fmt::format("# {} ({})\n{}", group->title, group->options, description_of(*parameter, group->options));
    }
    return text;
  }
  throw InvalidInput(fmt::format("describe: unknown parameter '{}', expected one of: {}", key,
                                 fmt::join(parameter_keys(), ", ")));
}

std::string described_all() {
  std::string text;
  for (const ParameterGroup& group : parameter_reference()) {
    text += fmt::format("# {} ({})\n", group.title, group.options);
    for (const ParameterText& parameter : group.parameters) text += description_of(parameter, group.options);
  }
  return text;
}

std::string reference_markdown() {
  std::string text =
      "# Parameter reference\n\n"
      "Generated from the parameter tables (include/needlekit/core/parameter.hpp) by\n"
      "`needlekit describe --all --markdown > docs/reference.md`; do not edit by hand (a test fails when this file\n"
      "is out of date). `needlekit describe KEY` prints one entry. Quantities are written with a unit in files\n"
      "(\"230 um\"); Python takes the field names of the last column in SI units.\n";
  for (const ParameterGroup& group : parameter_reference()) {
    text += fmt::format("\n## {}\n\n| key | kind | default | range | meaning | Python `{}.` |\n"
                        "| --- | --- | --- | --- | --- | --- |\n",
                        group.title, group.options);
    for (const ParameterText& parameter : group.parameters) {
      text += fmt::format("| `{}` | {} | `{}` | {} | {} | `{}` |\n", parameter.key, parameter.kind,
                          parameter.file_default(), escaped_for_table(parameter.range),
                          escaped_for_table(parameter.meaning), parameter.name);
    }
  }
  return text;
}

}  // namespace needlekit::reference
