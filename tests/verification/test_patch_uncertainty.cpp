// Patch uncertainty (issue 15, uncertainty/patch_uncertainty.hpp): with no spread the study is the deterministic
// `needlekit patch` evaluation; a uniform placement offset over a flat plate with an edge gives per-needle and
// patch probabilities that are ratios of lengths; the same seed gives bit-identical results on 1 and 2 threads;
// inputs that a patch case does not have are refused naming the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fmt/format.h>
#include <filesystem>

#include "../support/analytic_surfaces.hpp"
#include "../support/expect_invalid.hpp"
#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/patch_config.hpp"
#include "needlekit/io/patch_uncertainty_config.hpp"
#include "needlekit/uncertainty/patch_uncertainty.hpp"

using namespace needlekit;
using uncertainty::DesignEvent;
using uncertainty::DistributionKind;

namespace {

// A rigid 10 x 10 mm patch of 10 x 10 SU-8 cylinders (70 um x 400 um) pressed along -Z onto the plate
// [-10, 10]² mm (z = 0), centred at the origin: needle columns at u = -4.5, -3.5, ..., 4.5 mm.
struct PlateCase {
  geometry::SurfaceMesh surface{test::plane_grid_mesh(10e-3, 20)};
  uncertainty::PatchCase patch_case;
  PlateCase() {
    patch_case.surface = &surface;
    patch_case.design.needles_u = patch_case.design.needles_v = 10;
    patch_case.design.width_u = patch_case.design.width_v = 10e-3;
    patch_case.design.needle = {needle::Shape::Cylinder, 70e-6, 70e-6, 0, 400e-6};
    patch_case.design.material = materials::material_preset("su-8");
    patch_case.options.placement.center = Eigen::Vector3d::Zero();
    patch_case.options.fit.kind = patch::PatchKind::Rigid;
  }
};

uncertainty::DesignUncertainInput uniform(const std::string& key, double min, double max) {
  return {key, {DistributionKind::Uniform, 0, 0, 0, 0, min, max}};
}
uncertainty::DesignUncertainInput fixed_normal(const std::string& key) {
  uncertainty::DesignUncertainInput input{key, {DistributionKind::Normal, 0, 0}};
  input.centred_on_nominal = true;
  return input;
}

}  // namespace

TEST(PatchUncertainty, ZeroSpreadIsTheDeterministicPatchEvaluation) {
  // The flexible neck patch of §6.4.1 with every input at its nominal value (sd = 0): each needle's events are
  // those of fit_and_evaluate (`needlekit patch`), in every sample.
  const io::PatchCase c =
      io::read_patch_case(std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "examples/patch_neck_flexible.toml");
  const geometry::BodySurface body = geometry::read_body_surface(c.mesh, c.mesh_unit);
  const uncertainty::PatchCase patch_case{&body.surface, c.design, io::fit_and_evaluate_options(c)};
  const std::vector<uncertainty::DesignUncertainInput> inputs{
      fixed_normal("placement.offset_u"), fixed_normal("placement.rotation"), fixed_normal("tissue.alpha"),
      fixed_normal("needle.tip_diameter")};
  uncertainty::PatchUncertaintyOptions options;
  options.sampling.samples = 16;
  const uncertainty::PatchUncertaintyResult r = uncertainty::patch_uncertainty(patch_case, inputs, {}, options);
  const patch::FitAndEvaluateResult deterministic = patch::fit_and_evaluate(body.surface, c.design, patch_case.options);
  ASSERT_EQ(r.needles, 100);
  int ok = 0;
  for (int k = 0; k < r.needles; ++k) {
    const patch::NeedleState& s = deterministic.evaluation.needles[k];
    ok += s.status == "ok";
    EXPECT_EQ(r.needle_event(k, DesignEvent::Success).mean, s.status == "ok" ? 1.0 : 0.0) << k << " " << s.status;
    EXPECT_EQ(r.needle_event(k, DesignEvent::Puncture).mean, s.penetrates ? 1.0 : 0.0) << k;
    EXPECT_EQ(r.needle_event(k, DesignEvent::BucklingFailure).mean, s.buckles ? 1.0 : 0.0) << k;
    EXPECT_EQ(r.needle_event(k, DesignEvent::BendingFailure).mean, s.bends ? 1.0 : 0.0) << k;
    EXPECT_EQ(r.nominal.fit.positions[k], deterministic.fit.positions[k]);
  }
  EXPECT_EQ(r.success_fraction().mean, ok / 100.0);
  EXPECT_EQ(r.success_fraction().sd, 0.0);
  EXPECT_EQ(r.all_succeed().mean, ok == 100 ? 1.0 : 0.0);
  EXPECT_EQ(r.status, uncertainty::UncertaintyStatus::Ok);
  EXPECT_GT(ok, 50);  // the case works for most needles
}

TEST(PatchUncertainty, UniformOffsetOverAPlateEdgeGivesRatiosOfLengths) {
  // The centre moves by a uniform offset in [-8, 8] mm along U. A needle at u_i loses the plate (no surface under
  // it: no puncture) when u_i + offset leaves [-10, 10] mm, so P(success_i) = 1 − max(0, offset range beyond the
  // edge)/16 mm; every needle succeeds when |offset| <= 5.5 mm: P(all) = 11/16, P(>= 90 %) = P(|offset| <= 6.5 mm)
  // = 13/16 (a column of 10 needles is 10 % of the patch).
  const PlateCase plate;
  uncertainty::PatchUncertaintyOptions options;
  options.sampling.samples = 4096;
  options.sampling.seed = 7;
  options.sampling.sobol_indices = false;
  options.success_fractions = {0.9};
  const uncertainty::PatchUncertaintyResult r =
      uncertainty::patch_uncertainty(plate.patch_case, {uniform("placement.offset_u", -8e-3, 8e-3)}, {}, options);
  const auto expect_probability = [](const uncertainty::OutputSummary& s, double exact, const std::string& what) {
    EXPECT_NEAR(s.mean, exact, 5e-3) << what;
    EXPECT_LE(s.ci95.lo, exact + 1e-12) << what;
    EXPECT_GE(s.ci95.hi, exact - 1e-12) << what;
  };
  for (int i = 0; i < 10; ++i) {
    const double u = (-4.5 + i) * 1e-3;
    const double beyond = std::max(0.0, 8e-3 - (10e-3 - u)) + std::max(0.0, 8e-3 - (10e-3 + u));
    const double exact = 1 - beyond / 16e-3;
    for (int j : {0, 5, 9}) {
      const int k = i + 10 * j;
      expect_probability(r.needle_event(k, DesignEvent::Success), exact, fmt::format("needle {} success", k));
      expect_probability(r.needle_event(k, DesignEvent::Puncture), exact, fmt::format("needle {} puncture", k));
      EXPECT_EQ(r.needle_event(k, DesignEvent::BucklingFailure).mean, 0.0);
    }
  }
  expect_probability(r.all_succeed(), 11.0 / 16, "all succeed");
  expect_probability(r.at_least(0), 13.0 / 16, "at least 90 %");
  EXPECT_EQ(r.invalid_sample().mean, 0.0);
}

TEST(PatchUncertainty, SameSeedIsBitIdenticalOnOneAndTwoThreads) {
  const PlateCase plate;
  const std::vector<uncertainty::DesignUncertainInput> inputs{
      uniform("placement.offset_u", -6e-3, 6e-3), uniform("placement.offset_v", -6e-3, 6e-3),
      {"placement.rotation", {DistributionKind::Normal, 0, 0.2}},
      {"tissue.alpha", {DistributionKind::Lognormal, 0, 0, 0.0183, 0.3}}};
  for (const auto method : {uncertainty::SamplingMethod::MonteCarlo, uncertainty::SamplingMethod::Sobol}) {
    std::vector<uncertainty::PropagationResult> runs;
    for (const int threads : {1, 2}) {
      uncertainty::PatchUncertaintyOptions options;
      options.sampling.samples = 100;
      options.sampling.method = method;
      options.sampling.seed = 42;
      options.sampling.threads = threads;
      runs.push_back(uncertainty::patch_uncertainty(plate.patch_case, inputs, {{0, 3, 0.3}}, options).propagation);
    }
    ASSERT_EQ(runs[0].outputs.size(), runs[1].outputs.size());
    const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
    for (std::size_t o = 0; o < runs[0].outputs.size(); ++o) {
      const auto &a = runs[0].outputs[o], &b = runs[1].outputs[o];
      EXPECT_TRUE(same(a.mean, b.mean) && same(a.ci95.lo, b.ci95.lo) && same(a.ci95.hi, b.ci95.hi) && same(a.sd, b.sd))
          << a.name;
      for (std::size_t i = 0; i < a.first.size(); ++i) {
        EXPECT_TRUE(same(a.first[i].value, b.first[i].value) && same(a.total[i].value, b.total[i].value)) << a.name;
      }
    }
    EXPECT_EQ(runs[0].samples_of_output, runs[1].samples_of_output);
    EXPECT_GT(runs[0].outputs[0].sd, 0.0);  // the offsets do move needles off the plate
  }
}

TEST(PatchUncertainty, InputsThePatchCaseDoesNotHaveAreRefusedNamingTheKey) {
  const PlateCase plate;
  const auto transform = [&](const uncertainty::DesignUncertainInput& input) {
    std::vector<std::string> notes;
    uncertainty::patch_input_transform(plate.patch_case.design, plate.patch_case.options, {input}, {}, notes);
  };
  test::expect_invalid([&] { transform(uniform("array.width", 9e-3, 11e-3)); }, "array.width");  // the patch size is no input
  test::expect_invalid([&] { transform(uniform("insertion.angle", 0, 0.1)); }, "insertion.angle");
  test::expect_invalid([&] { transform(uniform("needle.bore_diameter", 10e-6, 20e-6)); }, "solid");
  test::expect_invalid([&] { transform({"placement.offset_u", {DistributionKind::Normal, 0, -1e-3}}); }, "placement.offset_u");
  test::expect_invalid([&] { transform(uniform("placement.offset_v", 1e-3, 1e-3)); }, "placement.offset_v");
  test::expect_invalid([&] { transform({"needle.tip_diameter", {DistributionKind::Normal, 70e-6, 35e-6}}); }, "physical range");
}
