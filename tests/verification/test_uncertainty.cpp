// The uncertainty engine against exact answers (issue 15, Verification):
//  - a normal Young's modulus on an Euler column: the buckling margin P_cr − F is linear in E, so P(buckling) is a
//    normal CDF; the Monte Carlo estimate lies within its interval and the interval shrinks as 1/√N;
//  - scrambled Sobol' points converge faster than Monte Carlo on the same case (the measured rates are printed);
//  - the Sobol' indices of the Ishigami function to 1e-2 with N = 2^14 scrambled Sobol' rows;
//  - every sd = 0 gives the deterministic evaluation;
//  - the same seed gives bit-identical results on 1 and 2 threads.
#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "needlekit/io/design_config.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

using namespace needlekit;
using uncertainty::DesignEvent;
using uncertainty::DistributionKind;

namespace {

// A solid silicon-like cylinder, Euler only (no yield strength), whose axial force |F(A)| is close to its critical
// load: P_cr = π²·E·I/(K·L)² is linear in E, so it buckles iff E <= E* = |F|·(K·L)²/(π²·I).
struct ExactCase {
  uncertainty::DesignCase design;
  double e_star = 0;  // Pa
  double mean = 0, sd = 0;
  double probability = 0;  // Φ((E* − μ)/σ)
};

ExactCase exact_case() {
  ExactCase c;
  needle::NeedleGeometry& n = c.design.design.needle;
  n.shape = needle::Shape::Cylinder;
  n.tip_diameter = n.base_diameter = 100e-6;
  n.length = 600e-6;
  c.design.design.material = {"euler", 4e9, std::nullopt, std::nullopt, "test"};
  c.design.design.needles_per_row = 10;
  c.design.design.width = 1e-2;
  const analysis::PerformanceIndexResult r =
      analysis::performance_index(c.design.design, c.design.conditions, c.design.options);
  c.e_star = r.buckling_force / r.buckling.critical_load * c.design.design.material.youngs_modulus;
  c.mean = 1.1 * c.e_star;
  c.sd = 0.12 * c.e_star;
  c.probability = boost::math::cdf(boost::math::normal_distribution<double>(c.mean, c.sd), c.e_star);
  return c;
}

uncertainty::DesignUncertaintyResult run_exact(const ExactCase& c, std::size_t samples,
                                               uncertainty::SamplingMethod method, std::uint64_t seed) {
  uncertainty::DesignUncertaintyOptions options;
  options.sampling.samples = samples;
  options.sampling.method = method;
  options.sampling.seed = seed;
  options.sampling.sobol_indices = false;
  uncertainty::Distribution e{DistributionKind::Normal, c.mean, c.sd};
  return uncertainty::design_uncertainty(c.design, {{"needle.material.youngs_modulus", e}}, {}, options);
}

// Least-squares slope of log(y) against log(x).
double log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

TEST(UncertaintyVerification, BucklingProbabilityOfNormalModulusIsTheNormalCdf) {
  const ExactCase c = exact_case();
  ASSERT_NEAR(c.probability, 0.2023, 1e-3);  // Φ(−0.1/0.12)
  std::vector<double> widths;
  for (const std::size_t n : {10'000u, 100'000u, 1'000'000u}) {
    const auto r = run_exact(c, n, uncertainty::SamplingMethod::MonteCarlo, 11);
    const uncertainty::OutputSummary& p = r.event(DesignEvent::BucklingFailure);
    EXPECT_LE(p.ci95.lo, c.probability) << n;
    EXPECT_GE(p.ci95.hi, c.probability) << n;
    widths.push_back(p.ci95.hi - p.ci95.lo);
  }
  // 1/√N: each tenfold N narrows the interval by √10 = 3.162.
  EXPECT_NEAR(widths[0] / widths[1], std::sqrt(10.0), 0.05);
  EXPECT_NEAR(widths[1] / widths[2], std::sqrt(10.0), 0.05);
}

TEST(UncertaintyVerification, ScrambledSobolConvergesFasterThanMonteCarlo) {
  const ExactCase c = exact_case();
  const std::vector<double> sizes{256, 1024, 4096, 16384};
  constexpr int kSeeds = 16;
  std::vector<double> rmse_mc, rmse_qmc;
  for (const double n : sizes) {
    double se_mc = 0, se_qmc = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const auto n_rows = static_cast<std::size_t>(n);
      const double mc = run_exact(c, n_rows, uncertainty::SamplingMethod::MonteCarlo, seed).event(DesignEvent::BucklingFailure).mean;
      const double qmc = run_exact(c, n_rows, uncertainty::SamplingMethod::Sobol, seed).event(DesignEvent::BucklingFailure).mean;
      se_mc += (mc - c.probability) * (mc - c.probability);
      se_qmc += (qmc - c.probability) * (qmc - c.probability);
    }
    rmse_mc.push_back(std::sqrt(se_mc / kSeeds));
    rmse_qmc.push_back(std::sqrt(se_qmc / kSeeds));
  }
  const double rate_mc = log_slope(sizes, rmse_mc), rate_qmc = log_slope(sizes, rmse_qmc);
  std::printf("RMSE of P(buckling), N = 256 .. 16384 (16 seeds): Monte Carlo N^%.2f, scrambled Sobol' N^%.2f\n",
              rate_mc, rate_qmc);
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    std::printf("  N = %5.0f  RMSE MC %.2e  Sobol' %.2e\n", sizes[i], rmse_mc[i], rmse_qmc[i]);
  }
  EXPECT_NEAR(rate_mc, -0.5, 0.15);
  EXPECT_LT(rate_qmc, -0.85);
  EXPECT_LT(rmse_qmc.back(), 0.2 * rmse_mc.back());
}

namespace {

// Ishigami & Homma 1990: f = sin x1 + a sin² x2 + b x3⁴ sin x1, x_i ~ U(−π, π), a = 7, b = 0.1.
class Ishigami : public uncertainty::Model {
public:
  const std::vector<uncertainty::OutputSpec>& outputs() const override { return outputs_; }
  void evaluate(const double* x, double* y) const override {
    y[0] = std::sin(x[0]) + 7 * std::sin(x[1]) * std::sin(x[1]) + 0.1 * std::pow(x[2], 4) * std::sin(x[0]);
  }

private:
  std::vector<uncertainty::OutputSpec> outputs_{{"f", uncertainty::OutputKind::Continuous}};
};

}  // namespace

TEST(UncertaintyVerification, IshigamiSobolIndicesToOneHundredth) {
  // Exact (Sobol' & Levitan 1999; Saltelli et al. 2008 §4.6): V = a²/8 + bπ⁴/5 + b²π⁸/18 + 1/2,
  // V1 = (1 + bπ⁴/5)²/2, V2 = a²/8, V13 = b²π⁸·(1/18 − 1/50), V3 = 0.
  const double a = 7, b = 0.1, pi4 = std::pow(M_PI, 4), pi8 = pi4 * pi4;
  const double v1 = 0.5 * (1 + b * pi4 / 5) * (1 + b * pi4 / 5), v2 = a * a / 8, v13 = b * b * pi8 * (1.0 / 18 - 1.0 / 50);
  const double v = v1 + v2 + v13;
  const double first[] = {v1 / v, v2 / v, 0.0}, total[] = {(v1 + v13) / v, v2 / v, v13 / v};
  std::vector<uncertainty::UncertainInput> inputs;
  for (const char* key : {"x1", "x2", "x3"}) inputs.push_back({key, {DistributionKind::Uniform, 0, 0, 0, 0, -M_PI, M_PI}});
  const uncertainty::InputTransform transform(inputs);
  uncertainty::PropagationOptions options;
  options.samples = 1u << 14;  // the documented sample size: 2^14 rows, 5·2^14 = 81920 runs
  options.method = uncertainty::SamplingMethod::Sobol;
  options.seed = 1990;
  const uncertainty::PropagationResult r = uncertainty::propagate(transform, Ishigami(), options);
  const uncertainty::OutputSummary& f = r.outputs[0];
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(f.first[i].value, first[i], 1e-2) << "S_" << i + 1;
    EXPECT_NEAR(f.total[i].value, total[i], 1e-2) << "ST_" << i + 1;
    // The replicate intervals cover the exact values.
    EXPECT_LE(f.first[i].ci95.lo, first[i] + 1e-3);
    EXPECT_GE(f.first[i].ci95.hi, first[i] - 1e-3);
  }
  EXPECT_NEAR(f.mean, a / 2, 2e-3);  // E f = a/2
  EXPECT_NEAR(f.sd * f.sd, v, 0.02 * v);
}

TEST(UncertaintyVerification, ZeroSpreadGivesTheDeterministicEvaluation) {
  const std::filesystem::path examples = std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "examples";
  for (const char* name : {"evaluate_table_6_1_cone.toml", "evaluate_table_6_1_bevel_hollow.toml",
                           "evaluate_table_6_1_cylinder.toml", "evaluate_table_6_1_cone_hollow.toml"}) {
    const io::DesignFile file = io::read_design_file(examples / name);
    const uncertainty::DesignCase design{file.design, file.conditions, file.options};
    const analysis::PerformanceIndexResult reference = analysis::performance_index(file.design, file.conditions, file.options);
    std::vector<uncertainty::DesignUncertainInput> inputs;
    for (const char* key : {"needle.tip_diameter", "needle.length", "tissue.alpha", "tissue.tau",
                            "needle.material.youngs_modulus", "insertion.target_depth"}) {
      inputs.push_back({key, {DistributionKind::Normal}, true});  // sd 0, centred on the design's value
    }
    uncertainty::DesignUncertaintyOptions options;
    options.sampling.samples = 64;
    const auto r = uncertainty::design_uncertainty(design, inputs, {}, options);
    EXPECT_EQ(r.index().mean, reference.performance_index) << name;
    EXPECT_EQ(r.index().sd, 0.0) << name;
    EXPECT_EQ(r.index().q05, reference.performance_index) << name;
    EXPECT_EQ(r.event(DesignEvent::BucklingFailure).mean, reference.buckling_ok ? 0.0 : 1.0) << name;
    EXPECT_EQ(r.event(DesignEvent::ReachesTarget).mean, reference.permeation_depth > 0 ? 1.0 : 0.0) << name;
    EXPECT_EQ(r.event(DesignEvent::Success).mean, reference.performance_index > 0 ? 1.0 : 0.0) << name;
    EXPECT_TRUE(std::isnan(r.index().first[0].value)) << "no variance, no Sobol' index";
  }
}

TEST(UncertaintyVerification, SameSeedIsBitIdenticalOnOneAndTwoThreads) {
  const ExactCase c = exact_case();
  std::vector<uncertainty::DesignUncertainInput> inputs{
      {"needle.material.youngs_modulus", {DistributionKind::Normal, c.mean, c.sd}},
      {"tissue.alpha", {DistributionKind::Lognormal, 0, 0, 0.0183, 0.3}},
      {"needle.length", {DistributionKind::Triangular, 0, 0, 0, 0, 550e-6, 650e-6, 600e-6}},
  };
  for (const auto method : {uncertainty::SamplingMethod::MonteCarlo, uncertainty::SamplingMethod::Sobol}) {
    std::vector<uncertainty::PropagationResult> runs;
    for (const int threads : {1, 2}) {
      uncertainty::DesignUncertaintyOptions options;
      options.sampling.samples = 5000;  // several blocks per group, and groups of unequal size
      options.sampling.method = method;
      options.sampling.seed = 42;
      options.sampling.threads = threads;
      runs.push_back(uncertainty::design_uncertainty(c.design, inputs, {{0, 1, 0.4}}, options).propagation);
    }
    ASSERT_EQ(runs[0].outputs.size(), runs[1].outputs.size());
    for (std::size_t o = 0; o < runs[0].outputs.size(); ++o) {
      const auto &a = runs[0].outputs[o], &b = runs[1].outputs[o];
      const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
      EXPECT_TRUE(same(a.mean, b.mean) && same(a.sd, b.sd) && same(a.ci95.lo, b.ci95.lo) && same(a.q50, b.q50)) << a.name;
      for (std::size_t i = 0; i < a.first.size(); ++i) {
        EXPECT_TRUE(same(a.first[i].value, b.first[i].value) && same(a.total[i].ci95.hi, b.total[i].ci95.hi)) << a.name;
      }
    }
    EXPECT_EQ(runs[0].samples_of_output, runs[1].samples_of_output);
    EXPECT_GT(runs[0].outputs[0].sd, 0.0);  // the inputs do vary
  }
}
