// The progress callback of uncertainty propagation (PropagationOptions::progress): fractions that never decrease and
// end at 1, a result that does not depend on it, and a callback returning false stops the run with Interrupted
// (what `needlekit serve` does when a job is cancelled).
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "needlekit/core/interrupt.hpp"
#include "needlekit/io/json_config.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

using namespace needlekit;

namespace {

io::UncertaintyFile su8_cone() {
  return io::parse_uncertainty_json(R"({"needle": {"shape": "cone", "tip_diameter": "70 um",
      "base_diameter": "200 um", "length": "600 um", "material": "su-8"}, "array": {"needles_per_row": 10,
      "width": "1 cm"}, "insertion": {"angle": "10 deg"},
      "uncertain": {"tissue.alpha": {"distribution": "lognormal", "sigma_log": 0.3},
                    "insertion.angle": {"distribution": "uniform", "min": "0 deg", "max": "20 deg"}},
      "sampling": {"samples": 4096, "seed": 3}})", "uncertainty.json");
}

}  // namespace

TEST(PropagationProgress, FractionsNeverDecreaseEndAtOneAndLeaveTheResultAlone) {
  const io::UncertaintyFile file = su8_cone();
  uncertainty::DesignUncertaintyOptions options;
  options.sampling = file.sampling;
  options.sampling.threads = 4;
  const auto without = uncertainty::design_uncertainty(file.design, file.inputs, file.correlations, options);
  std::vector<double> fractions;
  options.sampling.progress = [&fractions](double fraction) {
    fractions.push_back(fraction);  // one thread at a time: no lock needed
    return true;
  };
  const auto with = uncertainty::design_uncertainty(file.design, file.inputs, file.correlations, options);
  ASSERT_FALSE(fractions.empty());
  for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_LE(fractions[i - 1], fractions[i]);
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  EXPECT_EQ(with.event(uncertainty::DesignEvent::Success).mean, without.event(uncertainty::DesignEvent::Success).mean);
}

TEST(PropagationProgress, ACallbackReturningFalseStopsTheRun) {
  const io::UncertaintyFile file = su8_cone();
  uncertainty::DesignUncertaintyOptions options;
  options.sampling = file.sampling;
  options.sampling.threads = 2;
  std::atomic<int> calls = 0;
  options.sampling.progress = [&calls](double) { return ++calls < 2; };
  EXPECT_THROW(uncertainty::design_uncertainty(file.design, file.inputs, file.correlations, options), Interrupted);
  EXPECT_LT(calls.load(), 40);  // stopped early, not after every block
}
