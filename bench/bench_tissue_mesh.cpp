// Meshing the default skin block (dissertation §3.3: 3000 x 3000 x 1150 um, SC 20 um, EP to 160 um, DM below; one
// insertion site at the centre) with Gmsh (Delaunay 3D) at about 100k, 300k and 1M tetrahedra. Run one size per process
// to read its peak memory (peak_rss_MB is the process's maximum resident set so far):
//   build/bin/needlekit_bench --benchmark_filter='BM_SkinBlockMesh/1/'
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <filesystem>

#include "needlekit/io/tet_mesh_vtu.hpp"
#include "needlekit/io/vtu_writer.hpp"
#include "needlekit/mesh/layered_block_mesh.hpp"
#include "needlekit/mesh/tet_adjacency.hpp"
#include "skin_block_sizes.hpp"

using namespace needlekit;

namespace {

void BM_SkinBlockMesh(benchmark::State& state) {
  const mesh::LayeredBlockOptions options = bench::skin_block_options(static_cast<std::size_t>(state.range(0)));
  mesh::LayeredBlockResult result;
  for (auto _ : state) {
    result = mesh::layered_block_mesh(options);
    benchmark::DoNotOptimize(result.mesh.tets.data());
  }
  state.counters["tets"] = static_cast<double>(result.mesh.tets.size());
  state.counters["nodes"] = static_cast<double>(result.mesh.nodes.size());
  double min_quality = 1;
  for (const auto& q : result.quality) min_quality = std::min(min_quality, q.min_quality);
  state.counters["min_quality"] = min_quality;
  state.counters["sc_min_quality"] = result.quality.front().min_quality;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}
BENCHMARK(BM_SkinBlockMesh)->DenseRange(0, 2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

namespace {

// §3.3.3's data structures (faces, tet-tet and triangle-triangle adjacency, boundary surface) on the ~300k mesh.
void BM_TetTopologyAndBoundary(benchmark::State& state) {
  const mesh::TetMesh tissue = mesh::layered_block_mesh(bench::skin_block_options(1)).mesh;
  std::size_t boundary = 0;
  for (auto _ : state) {
    const mesh::TetTopology topology = mesh::tet_topology(tissue);
    boundary = mesh::boundary_surface(tissue, topology).triangles.size();
    benchmark::DoNotOptimize(boundary);
  }
  state.counters["tets"] = static_cast<double>(tissue.tets.size());
  state.counters["boundary_triangles"] = static_cast<double>(boundary);
}
BENCHMARK(BM_TetTopologyAndBoundary)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

namespace {

// Writing the ~300k mesh (points, tets, layer, E, nu, quality) as VTU, atomically, to the temporary folder.
void BM_WriteTissueVtu(benchmark::State& state) {
  const mesh::TetMesh tissue = mesh::layered_block_mesh(bench::skin_block_options(1)).mesh;
  const io::VtuGrid grid = io::tet_mesh_grid(tissue);
  const auto file = std::filesystem::temp_directory_path() / "needlekit_bench_tissue.vtu";
  for (auto _ : state) io::write_vtu(grid, file);
  state.counters["tets"] = static_cast<double>(tissue.tets.size());
  state.counters["file_MB"] = static_cast<double>(std::filesystem::file_size(file)) / 1e6;
  std::filesystem::remove(file);
}
BENCHMARK(BM_WriteTissueVtu)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
