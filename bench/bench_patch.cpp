// Benchmarks of patch fitting (issue 5, dissertation ch. 5, §6.4) on the 240k-triangle head-and-neck mesh
// (data/meshes, Visible Human Male skin, HuBMAP CCF, CC BY 4.0). Run: build/bin/needlekit_bench
//   --benchmark_filter=Patch
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#include "needlekit/materials/needle_material.hpp"
#include "needlekit/patch/placement_scan.hpp"

using namespace needlekit;
using namespace needlekit::patch;

namespace {

const std::filesystem::path kNeck =
    std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "data/meshes/vh_male_head_neck_loop2.obj";
constexpr int kAnteriorNeck = 2243;

const geometry::SurfaceMesh* neck() {
  static std::unique_ptr<geometry::SurfaceMesh> mesh;
  if (!mesh && std::filesystem::exists(kNeck)) {
    mesh = std::make_unique<geometry::SurfaceMesh>(geometry::read_triangle_mesh(kNeck, 1.0));
  }
  return mesh.get();
}

PatchDesign design_of(int n, double width) {
  PatchDesignOptions o;
  o.needles_u = o.needles_v = n;
  o.width_u = o.width_v = width;
  o.needle = {needle::Shape::Cylinder, 70e-6, 70e-6, 0, 400e-6};
  o.material = materials::material_preset("su-8");
  return patch_design(o);
}

void BM_Patch_LoadNeckMesh(benchmark::State& state) {
  if (!std::filesystem::exists(kNeck)) return state.SkipWithError("the shared meshes are missing");
  for (auto _ : state) {
    geometry::SurfaceMesh mesh(geometry::read_triangle_mesh(kNeck, 1.0));
    benchmark::DoNotOptimize(mesh.triangle_count());
  }
}
BENCHMARK(BM_Patch_LoadNeckMesh)->Unit(benchmark::kMillisecond)->Iterations(3);

// One fit of a 20 x 20 patch (§6.4.2) at the anterior neck after loading; kind = 0 rigid, 1 flexible, 2 equilibrium.
void BM_Patch_Fit20x20(benchmark::State& state) {
  const geometry::SurfaceMesh* surface = neck();
  if (!surface) return state.SkipWithError("the shared meshes are missing");
  const PatchDesign design = design_of(20, 20e-3);
  Placement placement;
  placement.center_vertex = kAnteriorNeck;
  const PatchFrame frame = patch_frame(*surface, placement, 0.03, 4e-4);
  FitOptions options;
  options.kind = static_cast<PatchKind>(state.range(0));
  options.flexible.max_spring_energy = 5e-4;
  for (auto _ : state) benchmark::DoNotOptimize(fit_patch(*surface, design, frame, options));
  state.SetLabel(std::string(to_string(options.kind)));
}
BENCHMARK(BM_Patch_Fit20x20)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// Fit + evaluation of every needle, 20 x 20 flexible (what `needlekit patch` does after loading).
void BM_Patch_FitAndEvaluate20x20(benchmark::State& state) {
  const geometry::SurfaceMesh* surface = neck();
  if (!surface) return state.SkipWithError("the shared meshes are missing");
  const PatchDesign design = design_of(20, 20e-3);
  Placement placement;
  placement.center_vertex = kAnteriorNeck;
  const PatchFrame frame = patch_frame(*surface, placement, 0.03, 4e-4);
  FitOptions options;
  options.flexible.max_spring_energy = 5e-4;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evaluate_needles(*surface, design, fit_patch(*surface, design, frame, options)));
  }
}
BENCHMARK(BM_Patch_FitAndEvaluate20x20)->Unit(benchmark::kMillisecond);

// 10,000 placements of a 10 x 10 flexible patch over the neck (vertices with 0.57 m < y < 0.70 m), each fitted
// along the surface normal and fully evaluated.
void BM_Patch_PlacementScan10000(benchmark::State& state) {
  const geometry::SurfaceMesh* surface = neck();
  if (!surface) return state.SkipWithError("the shared meshes are missing");
  std::vector<int> band;
  for (int v = 0; v < surface->vertex_count(); ++v) {
    const double y = surface->mesh().vertices[v].y();
    if (y > 0.57 && y < 0.70) band.push_back(v);
  }
  std::vector<int> vertices;
  for (int i = 0; i < 10000; ++i) vertices.push_back(band[static_cast<std::size_t>(i) * band.size() / 10000]);
  const PatchDesign design = design_of(10, 10e-3);
  PlacementScanOptions options;
  options.fit.flexible.max_spring_energy = 5e-5;
  int placed = 0;
  for (auto _ : state) {
    const auto scan = placement_scan(*surface, design, vertices, options);
    placed = 0;
    for (const auto& s : scan) placed += s.placed;
  }
  state.counters["placed"] = placed;
  state.counters["band_vertices"] = static_cast<double>(band.size());
}
BENCHMARK(BM_Patch_PlacementScan10000)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
