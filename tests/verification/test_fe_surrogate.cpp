// The FE surrogate (issue 15, uncertainty/fe_surrogate.hpp) on the coarse two-layer indentation
// (examples/indent_coarse_two_layers.toml, ~0.5 s per FE run): with no spread it is the single FE run; with
// lognormal layer modulus and critical pressure its stated validation error is small and holds at FE runs it has
// never seen.
#include <gtest/gtest.h>

#include <filesystem>

#include "needlekit/io/indentation_case.hpp"
#include "needlekit/uncertainty/fe_surrogate.hpp"

using namespace needlekit;
using uncertainty::DistributionKind;

namespace {

insertion::IndentationCase coarse_case() {
  return io::read_indentation_case(std::filesystem::path(NEEDLEKIT_SOURCE_DIR) /
                                   "examples/indent_coarse_two_layers.toml");
}

uncertainty::DesignUncertainInput lognormal(const std::string& key, double sigma_log) {
  uncertainty::DesignUncertainInput input{key, {DistributionKind::Lognormal, 0, 0, 1, sigma_log}};
  input.centred_on_nominal = true;  // median: the case's value
  return input;
}

}  // namespace

TEST(FeSurrogate, ZeroSpreadIsTheSingleFeRun) {
  const insertion::IndentationCase c = coarse_case();
  const insertion::IndentationResult fe = insertion::run_indentation(c);
  ASSERT_TRUE(fe.puncture);
  uncertainty::FeSurrogateOptions options;
  options.sampling.samples = 64;
  const uncertainty::FeSurrogateResult r = uncertainty::fe_surrogate(
      c, {lognormal("tissue.layers.0.youngs_modulus", 0), lognormal("puncture.critical_pressure", 0)}, {}, options);
  EXPECT_EQ(r.status, uncertainty::FeSurrogateStatus::Ok);
  EXPECT_TRUE(r.design.empty());  // nothing to fit: no FE run but the nominal one
  EXPECT_EQ(*r.nominal.depth, fe.puncture->depth);
  EXPECT_EQ(r.depth().mean, fe.puncture->depth);
  EXPECT_EQ(r.depth().sd, 0.0);
  EXPECT_EQ(r.force().q50, fe.puncture->force);
  EXPECT_EQ(r.punctures_before().mean, 1.0);
}

TEST(FeSurrogate, ReproducesHeldOutFeRunsWithinItsStatedError) {
  const insertion::IndentationCase c = coarse_case();
  uncertainty::FeSurrogateOptions options;
  options.sampling.samples = 4096;
  options.sampling.sobol_indices = false;
  options.validation_runs = 4;
  options.depth_limit = 100e-6;
  const uncertainty::FeSurrogateResult r = uncertainty::fe_surrogate(
      c, {lognormal("tissue.layers.0.youngs_modulus", 0.25), lognormal("puncture.critical_pressure", 0.15)}, {},
      options);
  ASSERT_EQ(r.status, uncertainty::FeSurrogateStatus::Ok) << r.reason;
  EXPECT_EQ(r.terms, 6);
  EXPECT_EQ(r.design.size(), 12u);
  ASSERT_EQ(r.validation.size(), 4u);
  EXPECT_LT(r.validation_depth_error.max, 0.05);
  EXPECT_LT(r.validation_force_error.max, 0.05);
  EXPECT_LE(r.validation_depth_error.rms, r.validation_depth_error.max);
  // Three more FE runs at points neither the fit nor the validation saw (the inputs' 10 % / 90 % quantiles and a
  // mixed point): the surrogate's error there stays within its stated error (with a margin of 2, as three points
  // are not the four it was checked on).
  const double e_nominal = 1e6, p_nominal = 0.3e6;
  for (const auto& [e, p] : {std::pair{e_nominal * 0.73, p_nominal * 1.21}, std::pair{e_nominal * 1.37, p_nominal * 0.83},
                             std::pair{e_nominal * 1.1, p_nominal * 1.1}}) {
    insertion::IndentationCase changed = c;
    changed.block.layers[0].youngs_modulus = e;
    changed.puncture.critical_pressure = p;
    const insertion::IndentationResult fe = insertion::run_indentation(changed);
    ASSERT_TRUE(fe.puncture);
    const double x[] = {e, p};
    double depth = 0, force = 0;
    r.surrogate(x, depth, force);
    EXPECT_LE(std::abs(depth - fe.puncture->depth) / fe.puncture->depth,
              std::max(2 * r.validation_depth_error.max, 0.01)) << e << " " << p;
    EXPECT_LE(std::abs(force - fe.puncture->force) / fe.puncture->force,
              std::max(2 * r.validation_force_error.max, 0.01)) << e << " " << p;
  }
  // The sampled distribution: the median near the nominal run, a probability with an interval.
  EXPECT_NEAR(r.depth().q50, *r.nominal.depth, 0.1 * *r.nominal.depth);
  EXPECT_GT(r.punctures_before().mean, 0.5);
  EXPECT_LT(r.punctures_before().mean, 1.0);
  EXPECT_LE(r.punctures_before().ci95.lo, r.punctures_before().mean);
}
