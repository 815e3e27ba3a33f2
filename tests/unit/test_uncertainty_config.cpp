// Uncertainty files: [uncertain], [sampling] and [[correlation]] parse with units, and every bad input of issue 15
// (negative sd, min >= max, an input the design lacks, a non-physical spread, samples < 2, an unknown
// distribution) is an InvalidInput whose message names FILE:LINE and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "needlekit/core/errors.hpp"
#include "needlekit/io/uncertainty_config.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

#include "../support/expect_invalid.hpp"

using namespace needlekit;
using needlekit::test::expect_invalid;

namespace {

// Line numbers matter: the [uncertain] table starts at line 12.
constexpr std::string_view kDesign = R"([needle]
shape = "cone"
tip_diameter = "30 um"
base_diameter = "150 um"
length = "500 um"
material = "silicon"

[array]
needles_per_row = 10
width = "1 cm"

[uncertain]
)";

io::UncertaintyFile parse(std::string_view uncertain, std::string_view rest = "") {
  return io::parse_uncertainty_toml(std::string(kDesign) + std::string(uncertain) + "\n" + std::string(rest), "uq.toml");
}

}  // namespace

TEST(UncertaintyConfig, ReadsDistributionsWithUnitsAndTheNominalAsDefaultMean) {
  const io::UncertaintyFile file = parse(
      R"("needle.tip_diameter" = { distribution = "normal", sd = "2 um" }
"tissue.alpha" = { distribution = "lognormal", median = "0.0183 N", sigma_log = 0.2 }
"needle.material.youngs_modulus" = { distribution = "triangular", min = "150 GPa", max = "180 GPa" }
insertion.angle = { distribution = "uniform", min = "0 deg", max = "10 deg" })",
      "[sampling]\nsamples = 1024\nmethod = \"monte-carlo\"\nseed = 7\n\n[[correlation]]\ninputs = [\"tissue.alpha\", "
      "\"needle.tip_diameter\"]\nrho = 0.5\n");
  ASSERT_EQ(file.inputs.size(), 4u);
  EXPECT_EQ(file.inputs[0].key, "needle.tip_diameter");
  EXPECT_TRUE(file.inputs[0].centred_on_nominal);
  EXPECT_DOUBLE_EQ(file.inputs[0].distribution.sd, 2e-6);
  EXPECT_FALSE(file.inputs[1].centred_on_nominal);
  EXPECT_DOUBLE_EQ(file.inputs[1].distribution.median, 0.0183);
  EXPECT_DOUBLE_EQ(file.inputs[2].distribution.mode, 165e9);  // the midpoint when mode is omitted
  EXPECT_EQ(file.inputs[3].key, "insertion.angle");           // a bare dotted key is flattened
  EXPECT_NEAR(file.inputs[3].distribution.max, 10 * M_PI / 180, 1e-15);
  EXPECT_EQ(file.sampling.samples, 1024u);
  EXPECT_EQ(file.sampling.method, uncertainty::SamplingMethod::MonteCarlo);
  EXPECT_EQ(file.sampling.seed, 7u);
  ASSERT_EQ(file.correlations.size(), 1u);
  EXPECT_EQ(file.correlations[0].first, 1u);
  EXPECT_EQ(file.correlations[0].second, 0u);
}

TEST(UncertaintyConfig, BadInputNamesFileLineAndKey) {
  expect_invalid([] { parse(R"("needle.tip_diameter" = { distribution = "normal", sd = "-2 um" })"); },
                 "uq.toml:13: key 'uncertain.\"needle.tip_diameter\"': sd -2e-06 is negative");
  expect_invalid([] { parse(R"("needle.length" = { distribution = "uniform", min = "500 um", max = "400 um" })"); },
                 "uq.toml:13: key 'uncertain.\"needle.length\"': min 0.0005 >= max 0.0004 (SI), expected min < max");
  expect_invalid([] { parse(R"("needle.colour" = { distribution = "normal", sd = "2 um" })"); },
                 "uq.toml:13: key 'uncertain.\"needle.colour\"': 'needle.colour' is not an input of the design");
  expect_invalid([] { parse(R"("needle.bore_diameter" = { distribution = "normal", sd = "2 um" })"); },
                 "uq.toml:13: uncertain.\"needle.bore_diameter\": the needle is solid");
  expect_invalid([] { parse(R"("needle.tip_diameter" = { distribution = "weibull", sd = "2 um" })"); },
                 "uq.toml:13: key 'uncertain.\"needle.tip_diameter\".distribution': unknown value 'weibull', expected "
                 "one of: \"normal\" | \"truncated-normal\" | \"lognormal\" | \"uniform\" | \"triangular\"");
  expect_invalid([] { parse(R"("needle.tip_diameter" = { distribution = "normal", sd = 2 })"); },
                 "key 'uncertain.\"needle.tip_diameter\".sd': 2 is a bare number without a unit");
  expect_invalid([] { parse(R"("needle.tip_diameter" = { distribution = "normal", median = "30 um", sd = "2 um" })"); },
                 "key 'uncertain.\"needle.tip_diameter\".median': does not apply to a normal distribution");
  expect_invalid([] { parse(R"("needle.tip_diameter" = { distribution = "normal", sd = "2 um" })",
                            "[sampling]\nsamples = 1\n"); },
                 "uq.toml:15: key 'sampling.samples': 1 is out of range, expected an integer in [2, 1e+08] (the "
                 "upper end is needlekit's work limit)");
  expect_invalid([] { parse(R"("needle.tip_diameter" = { distribution = "normal", sd = "2 um" })",
                            "[sampling]\nmethod = \"latin\"\n"); },
                 "key 'sampling.method': unknown value 'latin', expected one of: \"monte-carlo\" | \"sobol\"");
  expect_invalid([] { parse(""); }, "table [uncertain]: missing or empty");
}

// A normal tip diameter of 30 um with sd 15 um puts Φ(−2) = 2.3 % of the needles at a diameter <= 0: refused.
// With sd 8 um it is Φ(−3.75) = 0.0088 %: truncated, and the result says so.
TEST(UncertaintyConfig, NonPhysicalSpreadIsRefusedAboveATenthOfAPercentAndTruncatedBelow) {
  expect_invalid([] { parse(R"("needle.tip_diameter" = { distribution = "normal", mean = "30 um", sd = "15 um" })"); },
                 "uq.toml:13: uncertain.\"needle.tip_diameter\": normal(mean 30 um, sd 15 um) puts 2.28 % of its "
                 "samples outside the physical range [0, inf) um");
  const io::UncertaintyFile file =
      parse(R"("needle.tip_diameter" = { distribution = "normal", mean = "30 um", sd = "8 um" })");
  std::vector<std::string> notes;
  const uncertainty::InputTransform transform =
      uncertainty::design_input_transform(file.design, file.inputs, file.correlations, notes);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_THAT(notes[0], testing::HasSubstr("0.00884 % of normal(mean 30 um, sd 8 um) lies outside"));
  EXPECT_GT(transform.value(0, 1e-9), 0.0);  // the lowest quantile is still a positive diameter
}

TEST(UncertaintyConfig, CorrelationMustBeConsistent) {
  const std::string inputs = R"("tissue.alpha" = { distribution = "lognormal", sigma_log = 0.2 }
"tissue.tau" = { distribution = "lognormal", sigma_log = 0.2 }
"needle.length" = { distribution = "normal", sd = "5 um" })";
  expect_invalid([&] { parse(inputs, "[[correlation]]\ninputs = [\"tissue.alpha\", \"tissue.beta\"]\nrho = 0.5\n"); },
                 "'tissue.beta' is not in [uncertain]");
  expect_invalid([&] { parse(inputs, "[[correlation]]\ninputs = [\"tissue.alpha\", \"tissue.tau\"]\nrho = 1.5\n"); },
                 "key 'correlation.rho': 1.5 is not a number in (-1, 1)");
  // 0.9, 0.9 and -0.9 cannot hold together.
  expect_invalid([&] {
    parse(inputs, "[[correlation]]\ninputs = [\"tissue.alpha\", \"tissue.tau\"]\nrho = 0.9\n[[correlation]]\ninputs = "
                  "[\"tissue.alpha\", \"needle.length\"]\nrho = 0.9\n[[correlation]]\ninputs = [\"tissue.tau\", "
                  "\"needle.length\"]\nrho = -0.9\n");
  }, "not positive definite");
}

// [sampling] is read from uncertainty::kPropagationParameters: every key reads back, threads is not a key of the file,
// and propagate() checks the rows Python and the CLI may set.
TEST(UncertaintyConfig, SamplingIsReadAndCheckedFromItsParameterTable) {
  constexpr std::string_view kTip = R"("needle.tip_diameter" = { distribution = "normal", sd = "2 um" })";
  const io::UncertaintyFile file =
      parse(kTip, "[sampling]\nsamples = 256\nmethod = \"monte-carlo\"\nseed = 7\nsobol_indices = false\n"
                  "histogram_bins = 7\n");
  EXPECT_EQ(file.sampling.samples, 256u);
  EXPECT_EQ(file.sampling.method, uncertainty::SamplingMethod::MonteCarlo);
  EXPECT_EQ(file.sampling.seed, 7u);
  EXPECT_FALSE(file.sampling.sobol_indices);
  EXPECT_EQ(file.sampling.histogram_bins, 7);  // the one-line row change that made it a key of files
  expect_invalid([&] { parse(kTip, "[sampling]\nseed = -1\n"); },
                 "key 'sampling.seed': -1 is out of range, expected an integer >= 0");
  expect_invalid([&] { parse(kTip, "[sampling]\nthreads = 2\n"); }, "unknown key 'sampling.threads'");
  uncertainty::DesignUncertaintyOptions options;
  options.sampling = file.sampling;
  options.sampling.histogram_bins = 0;
  expect_invalid([&] { uncertainty::design_uncertainty(file.design, file.inputs, file.correlations, options); },
                 "sampling histogram_bins = 0: expected >= 1");
}
