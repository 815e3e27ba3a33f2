// Speed of the patch uncertainty study (issue 15): the 10 x 10 flexible neck patch of
// examples/uncertainty_patch_neck.toml (240k-triangle mesh, data/meshes) with 10^3 uncertain placements (offsets
// along U and V, rotation) and skin constants, each placed, fitted (node sweeping) and fully evaluated; goal < 30 s.
// Run: build/bin/needlekit_bench --benchmark_filter=PatchUncertainty
#include <benchmark/benchmark.h>

#include <filesystem>

#include "needlekit/geometry/body_surface.hpp"
#include "needlekit/io/patch_uncertainty_config.hpp"
#include "needlekit/uncertainty/patch_uncertainty.hpp"

using namespace needlekit;

namespace {

// range(0): samples; range(1): threads (0 = all).
void BM_PatchUncertainty10x10(benchmark::State& state) {
  const io::PatchUncertaintyFile file = io::read_patch_uncertainty_file(
      std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "examples/uncertainty_patch_neck.toml");
  const geometry::BodySurface body = geometry::read_body_surface(file.patch.mesh, file.patch.mesh_unit);
  const uncertainty::PatchCase patch_case{&body.surface, file.patch.design, io::fit_and_evaluate_options(file.patch)};
  uncertainty::PatchUncertaintyOptions options;
  options.sampling = file.sampling;
  options.sampling.samples = static_cast<std::size_t>(state.range(0));
  options.sampling.sobol_indices = false;
  options.sampling.threads = static_cast<int>(state.range(1));
  double all = 0, invalid = 0;
  for (auto _ : state) {
    const auto r = uncertainty::patch_uncertainty(patch_case, file.inputs, file.correlations, options);
    all = r.all_succeed().mean;
    invalid = r.invalid_sample().mean;
    benchmark::DoNotOptimize(r.propagation.outputs.data());  // (DoNotOptimize on a double clobbers it with this GCC)
  }
  state.counters["P_all_succeed"] = all;
  state.counters["P_invalid"] = invalid;
  state.counters["placements/s"] =
      benchmark::Counter(static_cast<double>(state.range(0)) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PatchUncertainty10x10)->Args({1000, 0})->Args({1000, 1})->Unit(benchmark::kSecond)->Iterations(1)
    ->UseRealTime();

}  // namespace
