// The parameter tables (core/parameter.hpp): every field of every tabled struct has exactly one row, the case reader
// accepts exactly the keys of the rows and reads each default back as the default, validation and the reader refuse
// a number outside its row's range naming the range, and docs/reference.md is what the tables generate.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>

#include "needlekit/calibration/calibration_solver_parameters.hpp"
#include "needlekit/core/parameter_text.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/insertion/loading_parameters.hpp"
#include "needlekit/insertion/insertion_curve_parameters.hpp"
#include "needlekit/insertion/post_puncture_parameters.hpp"
#include "needlekit/insertion/triangle_classification_parameters.hpp"
#include "needlekit/insertion/puncture_parameters.hpp"
#include "needlekit/io/tissue_config.hpp"
#include "needlekit/materials/needle_material.hpp"
#include "needlekit/mesh/layered_block_parameters.hpp"
#include "needlekit/uncertainty/fe_surrogate_parameters.hpp"
#include "needlekit/uncertainty/propagation_parameters.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/patch/fit_parameters.hpp"
#include "needlekit/patch/patch_design_parameters.hpp"
#include "needlekit/io/indentation_case.hpp"
#include "needlekit/io/insertion_case.hpp"
#include "needlekit/reference/parameter_reference.hpp"

namespace {

using namespace needlekit;
using testing::HasSubstr;

// Each row sets a different field: with field_count (the static_assert beside the table), one row per field.
template <class Options, class Table>
void expect_one_row_per_field(const Table& table, std::size_t callbacks) {
  EXPECT_EQ(std::tuple_size_v<Table> + callbacks, field_count<Options>());
  const Options options{};
  std::set<const void*> fields;
  std::set<std::string_view> keys, names;
  for_each_parameter(table, [&](const auto& row) {
    EXPECT_TRUE(fields.insert(&(options.*row.field)).second) << row.key << ": a second row for one field";
    EXPECT_TRUE(keys.insert(row.key).second) << row.key;
    EXPECT_TRUE(names.insert(row.attribute()).second) << row.attribute();
    EXPECT_FALSE(row.meaning.empty()) << row.key;
  });
}

TEST(ParameterTables, EveryFieldOfSolverOptionsHasOneRow) {
  expect_one_row_per_field<fem::SolverOptions>(fem::kSolverParameters, fem::kSolverCallbackFields);
}

TEST(ParameterTables, EveryFieldOfPunctureOptionsHasOneRow) {
  expect_one_row_per_field<insertion::PunctureOptions>(insertion::kPunctureParameters, 0);
}

TEST(ParameterTables, EveryFieldOfLoadingHasOneRow) {
  expect_one_row_per_field<insertion::Loading>(insertion::kLoadingParameters, 0);
}

TEST(ParameterTables, EveryFieldOfLayeredBlockOptionsHasOneRow) {
  expect_one_row_per_field<mesh::LayeredBlockOptions>(mesh::kLayeredBlockParameters, mesh::kLayeredBlockListFields);
}

// PropagationOptions and FeSurrogateOptions but their callbacks and the surrogate's nested sampling; the
// calibration's [solver] every field.
TEST(ParameterTables, EveryFieldOfTheUncertaintyAndCalibrationTablesHasOneRow) {
  expect_one_row_per_field<uncertainty::PropagationOptions>(uncertainty::kPropagationParameters,
                                                            uncertainty::kPropagationCallbackFields);
  expect_one_row_per_field<uncertainty::FeSurrogateOptions>(uncertainty::kFeSurrogateParameters,
                                                            uncertainty::kFeSurrogateOtherFields);
  expect_one_row_per_field<calibration::SolverSettings>(calibration::kCalibrationSolverParameters, 0);
}

TEST(ParameterTables, EveryFieldOfTheInsertionTablesHasOneRow) {
  expect_one_row_per_field<insertion::PostPunctureFitOptions>(insertion::kPostPunctureFitParameters, 0);
  expect_one_row_per_field<insertion::InsertionCurveOptions>(insertion::kInsertionCurveParameters, 0);
  expect_one_row_per_field<insertion::TriangleClassificationOptions>(
      insertion::kTriangleClassificationParameters, insertion::kTriangleClassificationVectorFields);
}

TEST(ParameterTables, EveryNumberOfPatchDesignOptionsHasOneRowAndPatchDesignChecksIt) {
  expect_one_row_per_field<patch::PatchDesignOptions>(patch::kPatchDesignParameters, patch::kPatchDesignOtherFields);
  patch::PatchDesignOptions options;
  options.needle = {needle::Shape::Cone, 30e-6, 150e-6, 0, 500e-6};
  options.material = materials::material_preset("silicon");
  EXPECT_EQ(patch::patch_design(options).node_count(), 100);
  options.width_v = -1e-3;
  EXPECT_THAT([&] { patch::patch_design(options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("patch design width_v = -0.001 m: expected > 0 m")));
  options.width_v = 10e-3;
  options.needles_u = 1;
  EXPECT_THAT([&] { patch::patch_design(options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("patch design needles_u = 1: expected in [2, 10000]")));
}

TEST(ParameterTables, EveryFieldOfPostPunctureOptionsHasOneRowButTheAxisPoint) {
  expect_one_row_per_field<insertion::PostPunctureOptions>(insertion::kPostPunctureParameters,
                                                           insertion::kPostPuncturePointFields);
}

TEST(ParameterTables, EveryFieldOfTheFitOptionsHasOneRowButCallbacksAndNestedOptions) {
  expect_one_row_per_field<patch::FlexibleFitOptions>(patch::kFlexibleFitParameters,
                                                      patch::kFlexibleFitCallbackFields);
  expect_one_row_per_field<patch::EquilibriumFitOptions>(patch::kEquilibriumFitParameters,
                                                         patch::kEquilibriumFitCallbackFields);
  expect_one_row_per_field<patch::FitOptions>(patch::kFitParameters, patch::kFitNestedFields);
}

// field_count on aggregates like the option structs (a callback, a string, nested aggregates: one field each).
struct ThreeFields {
  double number = 1;
  std::string text;
  std::function<void(int)> callback;
};
static_assert(field_count<ThreeFields>() == 3);
struct NestedFields {
  ThreeFields inner;
  int count = 0;
};
static_assert(field_count<NestedFields>() == 2);

const std::string kCase = "[needle]\nshape = \"cylinder\"\ntip_diameter = \"230 um\"\nlength = \"1 mm\"\n"
                          "[tissue]\npreset = \"silicone-0.2mpa\"\n[loading]\ndepth = \"10 um\"\n";

// A case that writes every key of [model] and [solver] with its default: the reader knows every key of the table
// (an unknown key is an error) and reads each default back.
TEST(ParameterTables, TheCaseReaderReadsEveryKeyOfTheSolverTableAtItsDefault) {
  std::string model = "[model]\n", solver = "[solver]\n";
  fem::SolverOptions defaults = io::case_solver_defaults();
  defaults.rezone = true;  // rezone_volume_ratio and max_remeshes apply only with it (an error otherwise)
  const std::vector<ParameterText> texts = parameter_texts(fem::kSolverParameters, defaults);
  for (const ParameterText& text : texts) {
    const std::size_t dot = text.key.find('.');
    ASSERT_NE(dot, std::string::npos) << text.key << ": every row of SolverOptions is written in a case file";
    (text.key.substr(0, dot) == "model" ? model : solver) +=
        fmt::format("{} = {}\n", text.key.substr(dot + 1), text.default_text);
  }
  const insertion::IndentationCase read = io::parse_indentation_case_toml(kCase + model + solver, "case.toml");
  const std::vector<ParameterText> read_texts = parameter_texts(fem::kSolverParameters, read.solver);
  ASSERT_EQ(read_texts.size(), texts.size());
  for (std::size_t i = 0; i < texts.size(); ++i) EXPECT_EQ(read_texts[i].default_text, texts[i].default_text);
}

TEST(ParameterTables, ValidationAndTheReaderRefuseANumberOutsideItsRangeNamingTheRange) {
  for_each_parameter(fem::kSolverParameters, [&](const auto& row) {
    if constexpr (requires { row.accepts(0.0); }) {
      SCOPED_TRACE(std::string(row.key));
      fem::SolverOptions options;
      options.*row.field = -1;  // below every row's range
      EXPECT_THAT([&] { options.validate(); },
                  testing::ThrowsMessage<InvalidInput>(
                      HasSubstr(fmt::format("solver {} = -1{}: expected {}{}", row.attribute(),
                                            si_unit_suffix(row), row.range(), si_unit_suffix(row)))));
      const std::string value = row.dimension == units::Dimension::Length ? "\"-1 um\"" : "-1";
      EXPECT_THAT([&] { io::parse_indentation_case_toml(kCase + fmt::format("[{}]\n{} = {}\n", row.group, row.key,
                                                                            value), "case.toml"); },
                  testing::ThrowsMessage<InvalidInput>(testing::AllOf(HasSubstr(fmt::format("'{}.{}'", row.group, row.key)),
                                                             HasSubstr(row.range()))));
    }
  });
}

// "[group]\nkey = default\n..." for every row of a table in `group` (a required row at its struct default too).
template <class Options, class Table>
std::string table_at_defaults(const Table& table, std::string_view group, const Options& defaults = Options{}) {
  std::string text = fmt::format("[{}]\n", group);
  for (const ParameterText& parameter : parameter_texts(table, defaults)) {
    const std::size_t dot = parameter.key.find('.');
    if (parameter.key.substr(0, dot) != group) continue;
    text += fmt::format("{} = {}\n", parameter.key.substr(dot + 1), parameter.default_text);
  }
  return text;
}

// The default texts of every row of `options`.
template <class Options, class Table>
std::vector<std::string> default_texts(const Table& table, const Options& options) {
  std::vector<std::string> texts;
  for (const ParameterText& parameter : parameter_texts(table, options)) texts.push_back(parameter.default_text);
  return texts;
}

// For each number of `group` whose range excludes -1: `read` of "[group]\nkey = -1 (in um, deg or SI)" throws naming the
// key and the range (a positive quantity: "is not positive", as the reader's positive_quantity_of says).
template <class Table, class Read>
void expect_the_reader_refuses_values_below_range(const Table& table, std::string_view group, Read&& read) {
  for_each_parameter(table, [&](const auto& row) {
    if constexpr (requires { row.accepts(0.0); }) {
      if (row.accepts(-1) || row.group != group) return;
      SCOPED_TRACE(std::string(row.key));
      const std::string unit = row.dimension == units::Dimension::Dimensionless ? ""
                               : row.dimension == units::Dimension::Angle   ? " deg"
                               : row.dimension == units::Dimension::Length  ? " um"
                                                                            : " " + std::string(units::si_symbol(row.dimension));
      const std::string value = unit.empty() ? "-1" : fmt::format("\"-1{}\"", unit);
      const bool positive = !unit.empty() && row.min == 0 && row.min_bound == Bound::Open && !std::isfinite(row.max);
      EXPECT_THAT([&] { read(fmt::format("{} = {}\n", row.key, value)); },
                  testing::ThrowsMessage<InvalidInput>(
                      testing::AllOf(HasSubstr(fmt::format("'{}.{}'", group, row.key)),
                                     HasSubstr(positive ? std::string("is not positive") : row.range()))));
    }
  });
}

// Every [loading] key at its default (the reader knows every key) reads back as the default.
TEST(ParameterTables, TheCaseReaderReadsEveryKeyOfTheLoadingTableAtItsDefault) {
  const std::string without_loading = kCase.substr(0, kCase.find("[loading]"));
  const insertion::IndentationCase read = io::parse_indentation_case_toml(
      without_loading + table_at_defaults<insertion::Loading>(insertion::kLoadingParameters, "loading"), "case.toml");
  EXPECT_EQ(default_texts(insertion::kLoadingParameters, static_cast<const insertion::Loading&>(read)),
            default_texts(insertion::kLoadingParameters, insertion::Loading{}));
  EXPECT_THAT([&] { io::parse_indentation_case_toml(without_loading + "[loading]\nsteps = 3\n", "case.toml"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("key 'loading.depth': missing")));
}

TEST(ParameterTables, TheCaseReaderRefusesALoadingValueOutsideItsRange) {
  const std::string without_loading = kCase.substr(0, kCase.find("[loading]"));
  expect_the_reader_refuses_values_below_range(insertion::kLoadingParameters, "loading", [&](const std::string& line) {
    const std::string depth = line.starts_with("depth") ? "" : "depth = \"10 um\"\n";
    io::parse_indentation_case_toml(without_loading + "[loading]\n" + depth + line, "case.toml");
  });
}

// Every key of [tissue] and [mesh] in the table at its default reads back as the default; the rows of no group are
// not keys of the file.
TEST(ParameterTables, TheTissueReaderReadsEveryKeyOfTheBlockTableAtItsDefault) {
  const auto& table = mesh::kLayeredBlockParameters;
  const io::TissueCase read = io::parse_tissue_case_toml(
      table_at_defaults<mesh::LayeredBlockOptions>(table, "tissue") + "preset = \"skin\"\n" +
          table_at_defaults<mesh::LayeredBlockOptions>(table, "mesh"),
      "case.toml");
  EXPECT_EQ(default_texts(table, read.block), default_texts(table, mesh::LayeredBlockOptions{}));
  EXPECT_THAT([] { io::parse_tissue_case_toml("[tissue]\npreset = \"skin\"\n[mesh]\nthreads = 2\n", "case.toml"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("unknown key 'mesh.threads'")));
}

TEST(ParameterTables, TheTissueReaderRefusesABlockValueOutsideItsRange) {
  for (const std::string group : {"tissue", "mesh"}) {
    expect_the_reader_refuses_values_below_range(mesh::kLayeredBlockParameters, group, [&](const std::string& line) {
      io::parse_tissue_case_toml(group == "tissue" ? "[tissue]\n" + line : "[tissue]\n[mesh]\n" + line, "case.toml");
    });
  }
}

const std::string kPostPuncture = "[post_puncture]\nstiffness = \"0.2 N/mm2\"\nscale = 0.168\nfinal_depth = \"1 mm\"\n";

// Every [post_puncture] key of the table at its default reads back as the default; tip_tolerance (no group) is not a
// key of the file.
TEST(ParameterTables, TheInsertionReaderReadsEveryKeyOfThePostPunctureTableAtItsDefault) {
  const auto& table = insertion::kPostPunctureParameters;
  const std::string rows = table_at_defaults<insertion::PostPunctureOptions>(table, "post_puncture");
  const io::InsertionSettings read =
      io::parse_insertion_settings(kPostPuncture + rows.substr(rows.find('\n') + 1), "case.toml");
  EXPECT_EQ(default_texts(table, read.post_puncture), default_texts(table, insertion::PostPunctureOptions{}));
  EXPECT_THAT([] { io::parse_insertion_settings(kPostPuncture + "tip_tolerance = 0.001\n", "case.toml"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("unknown key 'post_puncture.tip_tolerance'")));
}

// [post_puncture] from the fit's, the curve's and the classification's tables alone, every key at the struct's
// default, reads back as the defaults (the required stiffness, scale and final_depth included).
TEST(ParameterTables, TheInsertionReaderReadsEveryKeyOfTheFitCurveAndClassificationTablesAtTheirDefaults) {
  const auto rows = [](const auto& table, const auto& defaults) {
    const std::string text = table_at_defaults(table, "post_puncture", defaults);
    return text.substr(text.find('\n') + 1);
  };
  const auto& fit = insertion::kPostPunctureFitParameters;
  const auto& curve = insertion::kInsertionCurveParameters;
  const auto& classification = insertion::kTriangleClassificationParameters;
  const io::InsertionSettings read = io::parse_insertion_settings(
      "[post_puncture]\n" + rows(fit, insertion::PostPunctureFitOptions{}) +
          rows(curve, insertion::InsertionCurveOptions{}) +
          rows(classification, insertion::TriangleClassificationOptions{}),
      "case.toml");
  EXPECT_EQ(default_texts(fit, read.model), default_texts(fit, insertion::PostPunctureFitOptions{}));
  EXPECT_EQ(default_texts(curve, read.curve), default_texts(curve, insertion::InsertionCurveOptions{}));
  EXPECT_EQ(default_texts(classification, read.classification),
            default_texts(classification, insertion::TriangleClassificationOptions{}));
  EXPECT_THAT([] { io::parse_insertion_settings(kPostPuncture + "bore_radius = \"10 um\"\n", "case.toml"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("unknown key 'post_puncture.bore_radius'")));
}

TEST(ParameterTables, TheInsertionReaderAndValidationRefuseAPostPunctureValueOutsideItsRange) {
  expect_the_reader_refuses_values_below_range(
      insertion::kPostPunctureParameters, "post_puncture",
      [](const std::string& line) { io::parse_insertion_settings(kPostPuncture + line, "case.toml"); });
  for_each_parameter(insertion::kPostPunctureParameters, [](const auto& row) {
    if constexpr (requires { row.accepts(0.0); }) {
      insertion::PostPunctureOptions options;
      options.*row.field = -1;
      EXPECT_THAT([&] { insertion::post_puncture_loads(geometry::TriangleMesh{}, {}, options); },
                  testing::ThrowsMessage<InvalidInput>(
                      HasSubstr(fmt::format("post_puncture {} = -1{}: expected {}{}", row.attribute(),
                                            si_unit_suffix(row), row.range(), si_unit_suffix(row)))));
    }
  });
}

// A patch case of `kind` with `rows` in [patch].
io::PatchCase patch_case_with(std::string_view kind, const std::string& rows) {
  return io::parse_patch_case_toml(
      fmt::format("[surface]\nmesh = \"neck.obj\"\nunit = \"m\"\ncenter_vertex = 0\n[patch]\nkind = \"{}\"\n"
                  "size = \"10 mm\"\nneedles_per_row = 10\nspring_constant = \"1 N/mm\"\n{}[needle]\n"
                  "shape = \"cylinder\"\ntip_diameter = \"70 um\"\nlength = \"400 um\"\nmaterial = \"su-8\"\n",
                  kind, rows),
      "patch.toml", ".");
}

// The [patch] rows of a table at their defaults, without the table's header.
template <class Options, class Table>
std::string patch_rows_at_defaults(const Table& table) {
  const std::string rows = table_at_defaults<Options>(table, "patch");
  return rows.substr(rows.find('\n') + 1);
}

// Every [patch] key of the fit's tables at its default reads back as the default, each for its kind; kind is required.
TEST(ParameterTables, ThePatchReaderReadsEveryKeyOfTheFitTablesAtItsDefault) {
  const io::PatchCase flexible = patch_case_with(
      "flexible", patch_rows_at_defaults<patch::FlexibleFitOptions>(patch::kFlexibleFitParameters));
  EXPECT_EQ(default_texts(patch::kFlexibleFitParameters, flexible.fit.flexible),
            default_texts(patch::kFlexibleFitParameters, patch::FlexibleFitOptions{}));
  const io::PatchCase equilibrium = patch_case_with(
      "equilibrium", patch_rows_at_defaults<patch::EquilibriumFitOptions>(patch::kEquilibriumFitParameters));
  EXPECT_EQ(default_texts(patch::kEquilibriumFitParameters, equilibrium.fit.equilibrium),
            default_texts(patch::kEquilibriumFitParameters, patch::EquilibriumFitOptions{}));
  EXPECT_TRUE(equilibrium.load_given);
  EXPECT_THAT([] { patch_case_with("rigid", "contact_ratio = 2\n"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("unknown key 'patch.contact_ratio'")));
  EXPECT_THAT(reference::described("patch.kind"), HasSubstr("default: required in files (\"flexible\" in Python)"));
  EXPECT_THAT(reference::described("patch.max_spring_energy"), HasSubstr("range:   in (0, inf] J"));
}

TEST(ParameterTables, ThePatchReaderRefusesAFitValueOutsideItsRange) {
  expect_the_reader_refuses_values_below_range(patch::kFlexibleFitParameters, "patch", [](const std::string& line) {
    patch_case_with("flexible", line);
  });
  expect_the_reader_refuses_values_below_range(patch::kEquilibriumFitParameters, "patch", [](const std::string& line) {
    patch_case_with("equilibrium", line);
  });
}

// The optional quantities of [puncture]: absent, not given; given, read and checked against their range; described
// as optional with no default.
TEST(ParameterTables, TheOptionalPunctureQuantitiesAreNotGivenUnlessTheFileGivesThem) {
  EXPECT_FALSE(io::parse_indentation_case_toml(kCase, "case.toml").puncture.critical_pressure.has_value());
  const insertion::IndentationCase given = io::parse_indentation_case_toml(
      kCase + "[puncture]\ncritical_pressure = \"0.663 MPa\"\ntoughness = \"100 J/m2\"\n", "case.toml");
  EXPECT_DOUBLE_EQ(given.puncture.critical_pressure.value_or(0), 0.663e6);
  EXPECT_DOUBLE_EQ(given.puncture.toughness.value_or(0), 100);
  expect_the_reader_refuses_values_below_range(insertion::kPunctureParameters, "puncture", [](const std::string& line) {
    io::parse_indentation_case_toml(kCase + "[puncture]\n" + line, "case.toml");
  });
  insertion::PunctureOptions options;
  options.toughness = -1;
  EXPECT_THAT([&] { insertion::validate(options); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("puncture toughness = -1 N/m: expected > 0 N/m")));
  const std::string described = reference::described("puncture.critical_pressure");
  EXPECT_THAT(described, HasSubstr("kind:    optional quantity (pressure"));
  EXPECT_THAT(described, HasSubstr("default: optional: not given (None in Python)"));
  EXPECT_THAT(described, HasSubstr("range:   > 0 Pa"));
}

TEST(ParameterTables, DescribeNamesTheUnitDefaultAndRangeOfAKey) {
  const std::string friction = reference::described("solver.friction");
  EXPECT_THAT(friction, HasSubstr("Coulomb friction coefficient"));
  EXPECT_THAT(friction, HasSubstr("unit:    none"));
  EXPECT_THAT(friction, HasSubstr("default: 0\n"));
  EXPECT_THAT(friction, HasSubstr("range:   >= 0\n"));
  EXPECT_THAT(friction, HasSubstr("Python:  SolverOptions.friction"));
  EXPECT_THAT(reference::described("solver.boundary_tolerance"), HasSubstr("default: \"1e-09 m\""));
  // The defaults of case files: neo-Hookean and surface contact, not the struct's.
  EXPECT_THAT(reference::described("model.law"), HasSubstr("default: \"neo-hookean\""));
  EXPECT_THAT(reference::described("model.element"), HasSubstr("Python:  SolverOptions.order"));
  EXPECT_THAT(reference::described("loading.depth"), HasSubstr("default: required in files (\"0.0002 m\" in Python)"));
  EXPECT_THAT(reference::described("loading.continue_after_puncture"),
              testing::AllOf(HasSubstr("default: false\n"), HasSubstr("Python:  IndentationCase.stop_at_puncture")));
  // A key of two kinds of file is described for each, headed by where it is written.
  EXPECT_THAT(reference::described("solver.max_iterations"),
              testing::AllOf(HasSubstr("# indentation cases (`needlekit indent`), [model] and [solver]"),
                             HasSubstr("Newton iterations"), HasSubstr("# calibration files (`needlekit calibrate`)"),
                             HasSubstr("Levenberg-Marquardt iterations")));
  EXPECT_THAT([] { reference::described("solver.no_such_key"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr("unknown parameter 'solver.no_such_key', expected one "
                                                             "of: model.law, model.element")));
}

TEST(ParameterTables, DocsReferenceIsWhatTheTablesGenerate) {
  std::ifstream file(std::string(NEEDLEKIT_SOURCE_DIR) + "/docs/reference.md");
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_EQ(text.str(), reference::reference_markdown())
      << "docs/reference.md is out of date: needlekit describe --all --markdown > docs/reference.md";
  for (const std::string& key : reference::parameter_keys()) EXPECT_THAT(text.str(), HasSubstr("| `" + key + "` |"));
}

}  // namespace
