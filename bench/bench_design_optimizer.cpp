// Benchmarks of the analytical engine (issue: foundation). Run: build/bin/needlekit_bench
#include <benchmark/benchmark.h>

#include "needlekit/analysis/design_optimizer.hpp"
#include "needlekit/analysis/performance_index.hpp"

using namespace needlekit;
using namespace needlekit::analysis;

namespace {

constexpr needle::Shape kShapes[] = {needle::Shape::Cylinder, needle::Shape::Cone, needle::Shape::Bevel};

// One full performance_index() evaluation (every intermediate quantity, no memoization) per iteration, cycling
// through designs of all six types: "designs evaluated per second per core".
void BM_PerformanceIndexFullEvaluation(benchmark::State& state) {
  std::vector<ArrayDesign> designs;
  for (auto shape : kShapes) {
    for (double bore : {0.0, 20e-6}) {
      for (double d2 : {80e-6, 120e-6, 150e-6}) {
        ArrayDesign d;
        d.needle = {shape, shape == needle::Shape::Cylinder ? d2 : 40e-6, d2, bore, 500e-6};
        d.material = materials::material_preset("silicon");
        d.needles_per_row = 20;
        d.width = 1e-2;
        designs.push_back(d);
      }
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(performance_index(designs[i++ % designs.size()], InsertionConditions{}));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PerformanceIndexFullEvaluation);

// The Fig 6.20 grid, brute force, all six needle types in one iteration (2 threads on this machine).
void BM_Figure_6_20_AllSixTypes_BruteForce(benchmark::State& state) {
  std::uint64_t points = 0;
  for (auto _ : state) {
    for (auto shape : kShapes) {
      for (bool hollow : {false, true}) {
        OptimizerOptions options;
        options.top = 10;
        const auto r = optimize_design(figure_6_20_space(shape, hollow), options);
        points += r.evaluated;
        benchmark::DoNotOptimize(r);
      }
    }
  }
  state.counters["grid_points_per_s"] = benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Figure_6_20_AllSixTypes_BruteForce)->Unit(benchmark::kMillisecond)->UseRealTime();

// The certified optimum on the Fig 6.20 bounds with 1 um steps for D1, D2, D3, w and L (about 2e13 points for a
// hollow type), all six types in one iteration.
void BM_Certified_1um_AllSixTypes(benchmark::State& state) {
  for (auto _ : state) {
    for (auto shape : kShapes) {
      for (bool hollow : {false, true}) {
        DesignSpace space = figure_6_20_space(shape, hollow);
        space.tip_diameter.step = space.base_diameter.step = space.bore_diameter.step = 1e-6;
        space.width.step = space.length.step = 1e-6;
        OptimizerOptions options;
        options.method = SearchMethod::Certified;
        benchmark::DoNotOptimize(optimize_design(space, options));
      }
    }
  }
}
BENCHMARK(BM_Certified_1um_AllSixTypes)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
