// Speed of the uncertainty study (issue 15): 10^6 analytic samples with every event probability and the
// first-order and total Sobol' indices (Saltelli design, N·(k + 2) evaluations) on the Table 6.1 bevel.
#include <benchmark/benchmark.h>

#include "needlekit/io/design_config.hpp"
#include "needlekit/uncertainty/design_uncertainty.hpp"

using namespace needlekit;

namespace {

uncertainty::DesignCase bevel() {
  const io::DesignFile file =
      io::read_design_file(std::string(NEEDLEKIT_SOURCE_DIR) + "/examples/evaluate_table_6_1_bevel.toml");
  return {file.design, file.conditions, file.options};
}

// Tissue and material inputs with the nominal section (the usual study: who is the patient?), or with the tip
// diameter too (every sample a new section and its own buckling eigenvalue).
void run(benchmark::State& state, const std::vector<uncertainty::DesignUncertainInput>& inputs) {
  const uncertainty::DesignCase design = bevel();
  uncertainty::DesignUncertaintyOptions options;
  options.sampling.samples = static_cast<std::size_t>(state.range(0));
  options.sampling.sobol_indices = state.range(1) != 0;
  std::size_t evaluations = 0;
  for (auto _ : state) {
    const auto r = uncertainty::design_uncertainty(design, inputs, {}, options);
    evaluations = r.propagation.evaluations;
    benchmark::DoNotOptimize(r.index().mean);
  }
  state.counters["evaluations"] = static_cast<double>(evaluations);
  state.counters["evaluations/s"] = benchmark::Counter(static_cast<double>(evaluations) * state.iterations(),
                                                       benchmark::Counter::kIsRate);
}

using uncertainty::DistributionKind;

void BM_UncertaintyTissueAndMaterial(benchmark::State& state) {
  run(state, {{"tissue.alpha", {DistributionKind::Lognormal, 0, 0, 0.0183, 0.3}},
              {"tissue.tau", {DistributionKind::Lognormal, 0, 0, 6250, 0.2}},
              {"needle.material.youngs_modulus", {DistributionKind::Normal, 169e9, 10e9}}});
}
BENCHMARK(BM_UncertaintyTissueAndMaterial)->Args({1'000'000, 1})->Args({1'000'000, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_UncertaintyWithTipDiameter(benchmark::State& state) {
  run(state, {{"tissue.alpha", {DistributionKind::Lognormal, 0, 0, 0.0183, 0.3}},
              {"needle.tip_diameter", {DistributionKind::Normal, 30e-6, 2e-6}}});
}
BENCHMARK(BM_UncertaintyWithTipDiameter)->Args({10'000, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
