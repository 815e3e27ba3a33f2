// The enum tables (core/enum_table.hpp): names are unique and round-trip through value_of, every value has a
// meaning, and the functions that existed before the tables (fem's to_string / *_from_string, needle's
// shape_from_string, ...) say the same as the tables.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "needlekit/analysis/buckling.hpp"
#include "needlekit/analysis/sensitivity_sweep.hpp"
#include "needlekit/core/enum_table.hpp"
#include "needlekit/fem/quasi_static_solver.hpp"
#include "needlekit/fem/solver_parameters.hpp"
#include "needlekit/needle/needle_geometry.hpp"
#include "needlekit/patch/fit_patch.hpp"
#include "needlekit/patch/patch_placement.hpp"

namespace {

using namespace needlekit;
using testing::HasSubstr;

template <class Value, std::size_t N>
void expect_well_formed(const EnumTable<Value, N>& table) {
  std::set<std::string_view> names;
  std::set<Value> values;
  for (const EnumEntry<Value>& entry : table) {
    EXPECT_TRUE(names.insert(entry.name).second) << entry.name;
    EXPECT_TRUE(values.insert(entry.value).second) << entry.name;
    EXPECT_FALSE(entry.meaning.empty()) << entry.name;
    EXPECT_EQ(value_of(table, entry.name, "key"), entry.value);
    EXPECT_EQ(name_of(table, entry.value), entry.name);
  }
  EXPECT_THAT([&] { value_of(table, "no-such-name", "model.law"); },
              testing::ThrowsMessage<InvalidInput>(
                  HasSubstr("model.law: unknown value 'no-such-name', expected one of: " + choices_of(table))));
}

// fem's own names (quasi_static_solver.cpp) agree with its tables.
template <class Value, std::size_t N, class ToString, class FromString>
void expect_fem_agrees(const EnumTable<Value, N>& table, ToString to_string, FromString from_string) {
  expect_well_formed(table);
  for (const EnumEntry<Value>& entry : table) {
    EXPECT_EQ(to_string(entry.value), entry.name);
    EXPECT_EQ(from_string(std::string(entry.name), "key"), entry.value);
  }
}

TEST(EnumTables, FemNamesAgreeWithTheTables) {
  expect_fem_agrees(fem::kMaterialLawNames, [](auto v) { return fem::to_string(v); }, fem::material_law_from_string);
  expect_fem_agrees(fem::kElementOrderNames, [](auto v) { return fem::to_string(v); }, fem::element_order_from_string);
  expect_fem_agrees(fem::kContactModelNames, [](auto v) { return fem::to_string(v); }, fem::contact_model_from_string);
  expect_fem_agrees(fem::kBoundaryConditionNames, [](auto v) { return fem::to_string(v); },
                    fem::boundary_condition_from_string);
  expect_well_formed(fem::kLinearSolverNames);
  for (const auto& entry : fem::kLinearSolverNames) EXPECT_EQ(fem::to_string(entry.value), entry.name);
}

TEST(EnumTables, EveryTableIsWellFormedAndToStringReadsIt) {
  expect_well_formed(needle::kShapeNames);
  for (const auto& entry : needle::kShapeNames) EXPECT_EQ(needle::to_string(entry.value), entry.name);
  expect_well_formed(patch::kPatchKindNames);
  for (const auto& entry : patch::kPatchKindNames) EXPECT_EQ(patch::to_string(entry.value), entry.name);
  expect_well_formed(patch::kApproachNames);
  for (const auto& entry : patch::kApproachNames) EXPECT_EQ(patch::to_string(entry.value), entry.name);
  expect_well_formed(patch::kFirstNodeNames);
  expect_well_formed(patch::kWalkMethodNames);
  expect_well_formed(analysis::kEndConditionNames);
  expect_well_formed(analysis::kEffectiveLengthNames);
  expect_well_formed(analysis::kSweepParameterNames);
  for (const auto& entry : analysis::kSweepParameterNames) EXPECT_EQ(analysis::to_string(entry.value), entry.name);
  expect_well_formed(fem::kPredictorNames);
}

TEST(EnumTables, ChoicesAndMeaningsAreFormattedForTheHelp) {
  EXPECT_EQ(choices_of(needle::kShapeNames), "\"cylinder\" | \"cone\" | \"bevel\"");
  EXPECT_THAT(meanings_of(patch::kFirstNodeNames, "first_node"), HasSubstr("  first_node = \"corner\": N(0,0)"));
}

}  // namespace
