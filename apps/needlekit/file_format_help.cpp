#include "file_format_help.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "needlekit/analysis/buckling.hpp"
#include "needlekit/analysis/puncture_force_law.hpp"
#include "needlekit/core/parameter_text.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/insertion/loading_parameters.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/materials/tissue_presets.hpp"
#include "needlekit/mesh/layered_block_parameters.hpp"
#include "needlekit/needle/needle_geometry.hpp"
#include "needlekit/needle/rounded_edges.hpp"
#include "needlekit/patch/fit_parameters.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/patch_placement.hpp"
#include "needlekit/uncertainty/propagation_parameters.hpp"

namespace needlekit::cli {
namespace {

std::string quoted_list(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "\"" : " | \"") + name + "\"";
  return text;
}

// "  residual_tolerance = 1e-06   in (0, 1): meaning" per [solver] setting that is not a choice (the choices are
// listed with their names), from fem::kSolverParameters.
std::string solver_settings_help() {
  std::string text;
  constexpr std::string_view kGroup = "solver.";
  for (const ParameterText& parameter : parameter_texts(fem::kSolverParameters, io::case_solver_defaults())) {
    if (!parameter.key.starts_with(kGroup) || parameter.kind == "choice") continue;
    const std::string_view key = std::string_view(parameter.key).substr(kGroup.size());
    text += fmt::format("  {:<34} {}: {}\n", fmt::format("{} = {}", key, parameter.default_text),
                        parameter.range, parameter.meaning);
  }
  return text;
}

// [array]'s counts and lengths (insertion::kArrayCounts, kArrayLengths), with their defaults.
std::string array_settings_help() {
  std::string text;
  for (const auto& parameter : insertion::kArrayCounts) {
    text += fmt::format("               {:<26} {}: {}\n", fmt::format("{} = {}", parameter.key, parameter.default_value()),
                        parameter.range(), parameter.meaning);
  }
  for (const auto& parameter : insertion::kArrayLengths) {
    text += fmt::format("               {:<26} {} m: {}\n",
                        fmt::format("{} = \"{:g} um\"", parameter.key, parameter.default_value() * 1e6),
                        parameter.range(), parameter.meaning);
  }
  return text;
}

}  // namespace

std::string settings_help(const std::vector<ParameterText>& texts, std::string_view group, std::string_view label,
                          std::size_t indent) {
  const std::size_t width = std::max(indent, label.size() + 2);
  std::string text;
  for (const ParameterText& parameter : texts) {
    if (!parameter.key.starts_with(fmt::format("{}.", group))) continue;
    const std::string_view key = std::string_view(parameter.key).substr(group.size() + 1);
    const std::string assignment = parameter.required ? fmt::format("{} (required)", key)
                                                      : fmt::format("{} = {}", key, parameter.default_text);
    text += fmt::format("{:<{}}{:<30} {}: {}\n", text.empty() ? label : "", width, assignment, parameter.range,
                        parameter.meaning);
  }
  return text;
}

std::string uncertainty_file_help() {
  constexpr const char* kLabel = "  [sampling]";
  return fmt::format(
      R"(UQ file: a DESIGN file (below) or a patch case (`needlekit patch --help`) plus
  [uncertain]    one inline table per uncertain input, keyed by its design-file key, values with the input's unit:
                 "needle.tip_diameter" = {{ distribution = "normal", mean = "30 um", sd = "2 um" }}
                 "tissue.alpha" = {{ distribution = "lognormal", median = "0.0183 N", sigma_log = 0.2 }}
                 an omitted mean / median is the design's value. More than 0.1 % of a distribution outside the
                 input's physical range (e.g. a diameter <= 0) is an error; less is truncated and reported.
{}  [[correlation]] inputs = ["tissue.alpha", "tissue.tau"], rho = 0.5   (between normal scores, optional))",
      settings_help(parameter_texts<uncertainty::PropagationOptions>(uncertainty::kPropagationParameters), "sampling",
                    kLabel));
}

std::string design_file_help() {
  return fmt::format(
      R"(DESIGN file (TOML; every dimensional value is a string with its unit, a bare number is an error):
  [needle]     shape = {}
               tip_diameter = "30 um"      D1 > 0 (bevel: sagitta of the tip segment)
               base_diameter = "150 um"    D2 >= D1 (cone and bevel D1 < D2 in the optimizer; cylinder: omit, = D1)
               bore_diameter = "20 um"     0 < D3 < D1; omit for a solid needle
               length = "500 um"           L > 0
               material = "silicon"        a preset (see `needlekit materials`) or {{ youngs_modulus = "4 GPa",
                                           yield_strength = "60 MPa", allowable_stress = "40 MPa", name = "..." }}
  [array]      needles_per_row = 10        n >= 1 (n x n needles)
               width = "1 cm"              w > 0, patch width
               spacing_factor = 3          beta >= 0 of w >= beta*n*D2 (default 3; 0 disables)
  [tissue]     model = "skin"              "skin" | "brain" | {{ alpha = "0.0183 N", tau = "6.25 /mm",
                                           small_tip_slope = "0.0608 /um" }}   (default skin)
               puncture_force = "eq-4.2"   the puncture-force law F(A), laws below (default eq-4.2)
  [insertion]  angle = "0 deg"             [0, 90) deg from the surface normal (default 0)
               target_depth = "50 um"      T > 0, or application = "transdermal" (50 um) | "aesthetic" | "tattoo"
                                           (1.5 mm) | "brain" (1 mm); default transdermal
               buckling_safety_factor = 1, bending_safety_factor = 1   (>= 1)
               end_condition = {}   (default fixed-free)
               effective_length = {} (uniform columns: cylinders), johnson = true (Johnson formula for short
               columns))",
                     choices_of(needle::kShapeNames), choices_of(analysis::kEndConditionNames),
                     choices_of(analysis::kEffectiveLengthNames)) +
         "\n" + puncture_force_law_help();
}

std::string space_file_help() {
  return fmt::format(R"(SPACE file (TOML; every dimensional value is a string with its unit):
  shape = "cone"                 {}
  hollow = false                 true: a bore_diameter range is required
  material = "silicon"           a preset (see `needlekit materials`) or {{ youngs_modulus = "169 GPa", ... }}
  tissue = "skin"                "skin" | "brain" | {{ alpha = "0.0183 N", tau = "6.25 /mm" }}   (default skin)
  puncture_force = "eq-4.2"      the puncture-force law F(A), laws below (default eq-4.2)
  target_depth = "50 um"         T > 0 (default 50 um)
  spacing_factor = 3             beta >= 0 of w >= beta*n*D2 (default 3)
  [ranges]                       inclusive [min, max, step], min > 0, max >= min, step > 0
  needles_per_row = [5, 25, 1]   integers
  tip_diameter = ["30 um", "150 um", "10 um"]
  base_diameter = ["30 um", "300 um", "10 um"]   (a cylinder omits it: D2 = D1)
  bore_diameter = ["20 um", "50 um", "10 um"]    (hollow only)
  width = ["5000 um", "10000 um", "1000 um"]
  length = ["300 um", "500 um", "50 um"])",
                     choices_of(needle::kShapeNames)) +
         "\n" + puncture_force_law_help();
}

std::string puncture_force_law_help() {
  std::string help =
      "\nPuncture-force laws (puncture_force = NAME, or a table { law = NAME, ... } for the user laws; D = the tip's "
      "equivalent diameter sqrt(4A/pi)):\n";
  for (const auto& law : analysis::kPunctureForceLawKindNames) {
    help += fmt::format("  {:<16}{}\n  {:<16}  source: {}\n", law.name, law.meaning, "",
                        analysis::puncture_force_law_source(law.value));
  }
  help += "  linear-area: slope = \"0.00019 N/um2\", intercept = \"-0.66 N\"; linear-diameter: slope = \"4594 N/m\", "
          "intercept = \"-3 mN\";\n  table: tip_diameter = [\"5 um\", \"37 um\"], force = [\"20 mN\", \"167 mN\"]; "
          "any law: valid_tip_diameter = [\"min\", \"max\"]\n  Outside a law's validity range the result carries a note.";
  return help;
}

std::string block_settings_help(std::string_view group, std::string_view label) {
  return settings_help(parameter_texts<mesh::LayeredBlockOptions>(mesh::kLayeredBlockParameters), group, label);
}

std::string indentation_case_help() {
  return fmt::format(
      R"(CASE file (TOML; every dimensional value is a string with its unit, a bare number is an error):
  name = "flat punch"                optional, names the output files (default: the file name)
  [needle]     shape, tip_diameter, base_diameter, bore_diameter, length as in design files (material is ignored: the
               needle is rigid), or mesh = "needle.stl" + mesh_unit = "um" (needle frame: axis z, tip at max z)
               tip_height = "0 um"       >= 0, the tip's height above the surface at the start
               edge_radius = "{:g} um"     surface contact, parametric needle: its edges rounded with this radius
                                         (default {:g} um, or half the largest the tip allows; < D1/2)
  [[needles]]  x = "-800 um", y = "-800 um", tip_height   one entry per needle (default: one needle at 0, 0)
  [array]      instead of [[needles]]: the needle repeated; layout = {}, backing_plate = false (the plate's travel
               and force reported; the depth must stay below the needle's length), symmetry = {}
{}{}               height (default: sum of the layers), preset = {}
               or [[tissue.layers]] name, thickness (the last may be "rest"),
               youngs_modulus = "0.2 MPa", poisson_ratio = 0.49 (in (-1, 0.5))
{}               sites = [["x", "y"], ...] (one needle per site without [[needles]]); or file = "tissue.msh" + unit
               instead of the sizes (layers = physical groups). Without split, large blocks are meshed twice.
{}  [model]      law = {} (default neo-hookean), contact = {} (default surface),
               element = {} (default linear),
               boundary = {}
               (default sides-and-bottom-fixed)
  [solver]     optional: predictor = {}, linear_solver = {},
               volumetric = {}, backend = {}, and the settings below (shown with their defaults;
               `needlekit describe solver.KEY` for one, docs/reference.md for all)
  [puncture]   criterion = {} (default "dissertation"); critical_pressure = "0.663 MPa" and/or
               toughness = "100 J/m2" or toughness_from = {{ first = "a.csv", second = "b.csv", crack_area = "6661 um2" }}
               (Eq 3.16 from two insertions; CSV depth_um,force_N); averaged-pressure: critical_pressure and
               material_length = "50 um" (surface contact; docs/indentation.md)
Choices:
{}{}{}{}{}{}{}{}{}{}{}Settings of [solver]:
{})",
      needle::kTypicalEdgeRadius * 1e6, needle::kTypicalEdgeRadius * 1e6, choices_of(insertion::kArrayLayoutNames),
      choices_of(insertion::kArraySymmetryNames), array_settings_help(), block_settings_help("tissue", "  [tissue]"),
      quoted_list(materials::tissue_preset_names()), block_settings_help("mesh", "  [mesh]"),
      settings_help(parameter_texts<insertion::Loading>(insertion::kLoadingParameters), "loading", "  [loading]"),
      choices_of(fem::kMaterialLawNames),
      choices_of(fem::kContactModelNames), choices_of(fem::kElementOrderNames), choices_of(fem::kBoundaryConditionNames),
      choices_of(fem::kPredictorNames), choices_of(fem::kLinearSolverNames),
      choices_of(fem::kVolumetricFormulationNames), choices_of(fem::kSolverBackendNames),
      choices_of(insertion::kPunctureLawNames), meanings_of(fem::kMaterialLawNames, "law"),
      meanings_of(fem::kContactModelNames, "contact"), meanings_of(fem::kElementOrderNames, "element"),
      meanings_of(fem::kBoundaryConditionNames, "boundary"), meanings_of(fem::kPredictorNames, "predictor"),
      meanings_of(fem::kLinearSolverNames, "linear_solver"),
      meanings_of(fem::kVolumetricFormulationNames, "volumetric"), meanings_of(fem::kSolverBackendNames, "backend"),
      meanings_of(insertion::kArrayLayoutNames, "layout"),
      meanings_of(insertion::kArraySymmetryNames, "symmetry"), meanings_of(insertion::kPunctureLawNames, "criterion"),
      solver_settings_help());
}

namespace {

// [patch]'s quantities, one per line with default, range and meaning: the rows of patch::kFlexibleFitParameters and
// kEquilibriumFitParameters that are not choices (the choices are listed with their names).
std::string patch_quantities_help() {
  std::vector<ParameterText> texts = parameter_texts<patch::FlexibleFitOptions>(patch::kFlexibleFitParameters);
  for (ParameterText& text : parameter_texts<patch::EquilibriumFitOptions>(patch::kEquilibriumFitParameters)) {
    texts.push_back(std::move(text));
  }
  std::erase_if(texts, [](const ParameterText& text) { return text.kind == "choice"; });
  return settings_help(texts, "patch", "", 13);
}

}  // namespace

std::string patch_case_help() {
  return fmt::format(
      "Case file (quantities are strings with units):\n"
      "  [surface]  mesh = \"neck.obj\" (OBJ/STL/PLY/OFF, relative to the case file); unit = \"m\" | \"mm\" | "
      "\"15.8 mm\";\n"
      "             center_vertex = 2243 or center = [\"x mm\", \"y mm\", \"z mm\"]; rotation = \"0 deg\";\n"
      "             approach = {} (default \"-z\")\n"
      "  [patch]    kind = {} (required); size = \"10 mm\"; needles_per_row = 10;\n"
      "             spring_constant = \"1 N/mm\" or {{ u = , v = , diagonal = }};\n"
      "             first_node = {}; walk = {} (flexible)\n"
      "{}"
      "  [needle], [tissue], [insertion]  as in design files (see needlekit evaluate --help)\n"
      "Choices:\n{}{}{}{}",
      choices_of(patch::kApproachNames), choices_of(patch::kPatchKindNames), choices_of(patch::kFirstNodeNames),
      choices_of(patch::kWalkMethodNames), patch_quantities_help(), meanings_of(patch::kApproachNames, "approach"), meanings_of(patch::kPatchKindNames, "kind"),
      meanings_of(patch::kFirstNodeNames, "first_node"), meanings_of(patch::kWalkMethodNames, "walk"));
}

}  // namespace needlekit::cli
