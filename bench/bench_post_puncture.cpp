// Post-puncture force (§3.6): a 1000-sample force-depth curve for a ~50k-triangle needle surface mesh. Goal (issue 4):
// under 0.1 s. "Curve" reuses the precomputed loads; "Full" classifies the triangles and computes every load too.
#include <benchmark/benchmark.h>

#include "needlekit/insertion/post_puncture_force.hpp"
#include "needlekit/needle/needle_surface_mesh.hpp"

namespace {

using namespace needlekit;

// ~50k triangles: a 230 um needle, 1000 um long.
geometry::TriangleMesh bench_mesh(needle::Shape shape) {
  if (shape == needle::Shape::Cone) return needle::needle_surface_mesh({shape, 40e-6, 230e-6, 0, 1000e-6}, {500, 50});
  return needle::needle_surface_mesh({shape, 10e-6, 230e-6, 0, 1000e-6}, {1000, 50});
}

std::vector<double> depths() {
  std::vector<double> d(1000);
  for (std::size_t k = 0; k < d.size(); ++k) d[k] = 1.2e-3 * static_cast<double>(k + 1) / 1000.0;
  return d;
}

void BM_PostPunctureCurve(benchmark::State& state, needle::Shape shape, bool full) {
  const auto mesh = bench_mesh(shape);
  const auto samples = depths();
  auto loads = insertion::post_puncture_loads(mesh);
  for (auto _ : state) {
    if (full) loads = insertion::post_puncture_loads(mesh);
    auto forces = insertion::post_puncture_forces(loads, samples, 0.2e6, 0.168);
    benchmark::DoNotOptimize(forces.data());
  }
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
  state.counters["loaded"] = static_cast<double>(loads.triangles.size());
}

BENCHMARK_CAPTURE(BM_PostPunctureCurve, Cone_Curve, needle::Shape::Cone, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PostPunctureCurve, Cone_Full, needle::Shape::Cone, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PostPunctureCurve, Bevel_Curve, needle::Shape::Bevel, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PostPunctureCurve, Bevel_Full, needle::Shape::Bevel, true)->Unit(benchmark::kMillisecond);

}  // namespace
