// §6.2 (tests/data/regression/section_6_2_insertion.json): the three experiment needles in silicone rubber, run from
// the shipped insert examples in a quick mode (coarse mesh, few steps, FE to 400 um): the puncture ordering of the
// experiment and of the dissertation's simulation — sharp bevel before blunt bevel before flat cylinder, in depth and
// in force — and a complete curve with a relaxation drop for each bevel. With the locking-free linear tetrahedra
// (nodal-averaged volume, the default at nu = 0.49) the cylinder does not puncture within the 400 um simulated
// here (the dissertation's simulation: > 500 um; the experiment: none within 2 mm). Magnitudes are reported in
// docs/post-puncture.md.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "needlekit/insertion/complete_insertion.hpp"
#include "needlekit/io/insertion_case.hpp"

using namespace needlekit;

namespace {

struct Outcome {
  insertion::PuncturePoint puncture;
  insertion::InsertionCurve curve;
  double final_force = 0;  // N, at the last simulated step
};

Outcome run_example(const std::string& name, bool punctures = true) {
  io::InsertionCase c = io::read_insertion_case(std::string(NEEDLEKIT_SOURCE_DIR) + "/examples/insert_" + name + ".toml");
  c.indentation.block.size_at_site = 40e-6;
  c.indentation.block.size_far = 600e-6;
  c.indentation.depth = 400e-6;
  c.indentation.steps = 8;
  c.options.curve.cutting_samples = 20;
  const insertion::CompleteInsertionResult result = insertion::complete_insertion(c.indentation, c.options);
  EXPECT_TRUE(result.indentation) << name << ": " << result.reason;
  if (!result.indentation) return {};
  const insertion::IndentationResult& run = *result.indentation;
  EXPECT_EQ(run.puncture.has_value(), punctures) << name << ": " << result.reason;
  const double final_force = run.steps.empty() ? 0.0 : run.steps.back().force;
  if (!run.puncture) {
    EXPECT_EQ(run.status, insertion::IndentationStatus::ReachedDepth) << name << ": " << run.reason;
    return {{}, {}, final_force};
  }
  return {*run.puncture, result.curve, final_force};
}

TEST(Section6_2, SharpBevelPuncturesBeforeBluntBevelBeforeCylinder) {
  std::ifstream data(NEEDLEKIT_TEST_DATA_DIR "/regression/section_6_2_insertion.json");
  const auto published = nlohmann::json::parse(data);
  ASSERT_LT(published["experiment"]["sharp_bevel"]["puncture_depth_mm"].get<double>(),
            published["experiment"]["blunt_bevel"]["puncture_depth_mm"].get<double>());
  const Outcome sharp = run_example("sharp_bevel"), blunt = run_example("blunt_bevel"),
                cylinder = run_example("cylinder", false);
  EXPECT_LT(sharp.puncture.depth, blunt.puncture.depth);
  EXPECT_LT(blunt.puncture.depth, 400e-6);
  EXPECT_LT(sharp.puncture.force, blunt.puncture.force);
  EXPECT_LT(blunt.puncture.force, cylinder.final_force);  // the cylinder carries more without puncturing
  // The dissertation's simulation: < 20 um; the experiment 230 um. needlekit (locking-free nodal-averaged tetrahedra,
  // reproducible Delaunay meshes): 101 um on this 40 um mesh, 48 um on the full run's 20 um mesh.
  EXPECT_LT(sharp.puncture.depth, 150e-6);
  for (const Outcome* o : {&sharp, &blunt}) {
    ASSERT_EQ(o->curve.punctures.size(), 1u);
    EXPECT_GT(o->curve.punctures.front().drop, 0.0);  // the relaxation drop of Fig 6.9
    EXPECT_EQ(o->curve.status, insertion::InsertionStatus::Complete);
  }
}

}  // namespace
