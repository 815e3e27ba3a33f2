// Every enum's table (core/enum_table.hpp): one row per enumerator (found with core/enumerator_name.hpp, so a new
// enumerator without a row fails here), unique names and values, a meaning per row, names that round-trip through
// value_of, and a to_string (where the enum has one) and *_from_string functions that say what the table says.
// The Python side: python/tests/test_enums.py.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "needlekit/analysis/buckling.hpp"
#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/analysis/performance_index.hpp"
#include "needlekit/analysis/puncture_force_law.hpp"
#include "needlekit/analysis/sensitivity_sweep.hpp"
#include "needlekit/calibration/calibrate.hpp"
#include "needlekit/calibration/calibration_problem.hpp"
#include "needlekit/core/enum_table.hpp"
#include "needlekit/core/enumerator_name.hpp"
#include "needlekit/core/exit_codes.hpp"
#include "needlekit/core/units.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/geometry/geodesic_distance.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"
#include "needlekit/geometry/surface_mesh.hpp"
#include "needlekit/insertion/complete_insertion.hpp"
#include "needlekit/insertion/force_curve.hpp"
#include "needlekit/insertion/indentation.hpp"
#include "needlekit/insertion/insertion_curve.hpp"
#include "needlekit/insertion/needle_array.hpp"
#include "needlekit/insertion/triangle_classification.hpp"
#include "needlekit/needle/needle_geometry.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/fitted_patch.hpp"
#include "needlekit/patch/flexible_fit.hpp"
#include "needlekit/patch/patch_design.hpp"
#include "needlekit/patch/patch_placement.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"
#include "needlekit/uncertainty/distribution.hpp"
#include "needlekit/uncertainty/fe_surrogate.hpp"
#include "needlekit/uncertainty/robust_design.hpp"
#include "needlekit/uncertainty/sample_points.hpp"

namespace {

using namespace needlekit;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::IsEmpty;

// What is wrong with an enum's table, one line per problem (empty: nothing). Limit bounds the enumerator scan.
template <const auto& Table, std::size_t Limit = 64>
std::vector<std::string> table_problems() {
  using Enum = decltype(Table[0].value);
  std::vector<std::string> problems;
  std::set<std::string_view> names;
  std::set<Enum> values;
  for (const auto& entry : Table) {
    if (!names.insert(entry.name).second) problems.push_back("name '" + std::string(entry.name) + "' twice");
    if (!values.insert(entry.value).second) problems.push_back("value of '" + std::string(entry.name) + "' twice");
    if (entry.meaning.empty()) problems.push_back("'" + std::string(entry.name) + "' has no meaning");
    if (value_of(Table, entry.name, "key") != entry.value) problems.push_back("'" + std::string(entry.name) + "'");
    if constexpr (requires { to_string(entry.value); }) {  // the enum's own to_string, found by ADL
      if (to_string(entry.value) != entry.name) {
        problems.push_back("to_string says '" + std::string(to_string(entry.value)) + "', the table '" +
                           std::string(entry.name) + "'");
      }
    }
  }
  if constexpr (std::is_enum_v<Enum>) {  // not kPredictorNames, a table of bool
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      constexpr auto enumerators = named_enumerators<Enum, Limit>();
      ((values.count(enumerators[I]) == 0
            ? problems.push_back("enumerator " + std::string(enumerator_name<enumerators[I]>()) + " has no row")
            : void()),
       ...);
    }(std::make_index_sequence<named_enumerators<Enum, Limit>().size()>{});
  }
  return problems;
}

// A reader of an enum's names (needle::shape_from_string, ...) takes every name of the table to its value.
template <class Value, std::size_t N, class FromString>
void expect_reader_agrees(const EnumTable<Value, N>& table, FromString from_string) {
  for (const EnumEntry<Value>& entry : table) EXPECT_EQ(from_string(std::string(entry.name), "key"), entry.value);
}

// A table with a defect of each kind, to show that table_problems finds them.
enum class Colour { Red, Green, Blue };
inline constexpr EnumTable<Colour, 2> kColourNames{{
    {Colour::Red, "red", "the first"},
    {Colour::Green, "green", ""},
}};
std::string_view to_string(Colour colour) { return colour == Colour::Red ? "rouge" : "green"; }

TEST(EnumTables, TheCheckFindsAMissingRowAWrongToStringAndAMissingMeaning) {
  EXPECT_THAT(table_problems<kColourNames>(),
              ElementsAre("to_string says 'rouge', the table 'red'", "'green' has no meaning",
                          "enumerator Blue has no row"));
}

TEST(EnumTables, CoreAndGeometry) {
  EXPECT_THAT(table_problems<units::kDimensionNames>(), IsEmpty());
  EXPECT_THAT((table_problems<kExitCodeNames, 256>()), IsEmpty());
  EXPECT_THAT(table_problems<geometry::kPathStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<geometry::kDistanceStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<geometry::kMeshFormatNames>(), IsEmpty());
  for (const auto& entry : units::kDimensionNames) EXPECT_EQ(units::dimension_name(entry.value), entry.name);
}

TEST(EnumTables, NeedleAndAnalysis) {
  EXPECT_THAT(table_problems<needle::kShapeNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kEndConditionNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kEffectiveLengthNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kBucklingMethodNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kSweepParameterNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kPerformanceStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kSearchMethodNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kOptimizerStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<analysis::kPunctureForceLawKindNames>(), IsEmpty());
  expect_reader_agrees(needle::kShapeNames, needle::shape_from_string);
  expect_reader_agrees(analysis::kPunctureForceLawKindNames, analysis::puncture_force_law_from_string);
}

TEST(EnumTables, Fem) {
  EXPECT_THAT(table_problems<fem::kMaterialLawNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kElementOrderNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kContactModelNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kLinearSolverNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kSolverBackendNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kBoundaryConditionNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kVolumetricFormulationNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kPredictorNames>(), IsEmpty());
  EXPECT_THAT(table_problems<fem::kStepStatusNames>(), IsEmpty());
  expect_reader_agrees(fem::kMaterialLawNames, fem::material_law_from_string);
  expect_reader_agrees(fem::kElementOrderNames, fem::element_order_from_string);
  expect_reader_agrees(fem::kContactModelNames, fem::contact_model_from_string);
  expect_reader_agrees(fem::kBoundaryConditionNames, fem::boundary_condition_from_string);
  expect_reader_agrees(fem::kVolumetricFormulationNames, fem::volumetric_formulation_from_string);
}

TEST(EnumTables, PatchAndInsertion) {
  EXPECT_THAT(table_problems<patch::kPatchKindNames>(), IsEmpty());
  EXPECT_THAT(table_problems<patch::kApproachNames>(), IsEmpty());
  EXPECT_THAT(table_problems<patch::kFirstNodeNames>(), IsEmpty());
  EXPECT_THAT(table_problems<patch::kWalkMethodNames>(), IsEmpty());
  EXPECT_THAT(table_problems<patch::kFitStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<patch::kSpringDirectionNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kTriangleClassNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kPunctureCriterionNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kIndentationStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kCompleteInsertionStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kInsertionPhaseNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kInsertionStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kArrayLayoutNames>(), IsEmpty());
  EXPECT_THAT(table_problems<insertion::kArraySymmetryNames>(), IsEmpty());
}

TEST(EnumTables, UncertaintyAndCalibration) {
  EXPECT_THAT(table_problems<uncertainty::kDistributionKindNames>(), IsEmpty());
  EXPECT_THAT(table_problems<uncertainty::kSamplingMethodNames>(), IsEmpty());
  EXPECT_THAT(table_problems<uncertainty::kDesignEventNames>(), IsEmpty());
  EXPECT_THAT(table_problems<uncertainty::kUncertaintyStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<uncertainty::kRobustStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<uncertainty::kFeSurrogateStatusNames>(), IsEmpty());
  EXPECT_THAT(table_problems<calibration::kExperimentKindNames>(), IsEmpty());
  EXPECT_THAT(table_problems<calibration::kCalibrationStatusNames>(), IsEmpty());
  expect_reader_agrees(uncertainty::kDistributionKindNames, uncertainty::distribution_kind_from_string);
  expect_reader_agrees(uncertainty::kSamplingMethodNames, uncertainty::sampling_method_from_string);
}

TEST(EnumTables, ValueOfNamesTheKeyAndListsTheChoices) {
  EXPECT_THAT([] { value_of(needle::kShapeNames, "no-such-name", "needle.shape"); },
              testing::ThrowsMessage<InvalidInput>(HasSubstr(
                  "needle.shape: unknown value 'no-such-name', expected one of: \"cylinder\" | \"cone\" | \"bevel\"")));
}

TEST(EnumTables, ChoicesAndMeaningsAreFormattedForTheHelp) {
  EXPECT_EQ(choices_of(needle::kShapeNames), "\"cylinder\" | \"cone\" | \"bevel\"");
  EXPECT_THAT(meanings_of(patch::kFirstNodeNames, "first_node"), HasSubstr("  first_node = \"corner\": N(0,0)"));
}

}  // namespace
