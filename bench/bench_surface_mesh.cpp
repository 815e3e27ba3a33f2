// Benchmarks of the surface model (issue 5, §5.6): loading and indexing the 240k-triangle neck mesh, closest-point
// and ray queries, geodesic traces and distances at patch-spring scale. Run: build/bin/needlekit_bench
//   --benchmark_filter=Neck
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <filesystem>
#include <memory>
#include <random>

#include "needlekit/geometry/cutting_plane_trace.hpp"
#include "needlekit/geometry/geodesic_distance.hpp"
#include "needlekit/geometry/geodesic_trace.hpp"
#include "needlekit/geometry/surface_mesh.hpp"

using namespace needlekit;
using namespace needlekit::geometry;

namespace {

const std::filesystem::path kNeck = NEEDLEKIT_SOURCE_DIR "/data/meshes/vh_male_head_neck_loop2.obj";
constexpr int kAnteriorNeck = 2243;  // README's suggested patch centre

const SurfaceMesh* neck() {
  static const std::unique_ptr<SurfaceMesh> mesh =
      std::filesystem::exists(kNeck) ? std::make_unique<SurfaceMesh>(read_triangle_mesh(kNeck, 1.0)) : nullptr;
  return mesh.get();
}

Eigen::AlignedBox3d box_of(const SurfaceMesh& s) {
  Eigen::AlignedBox3d box;
  for (const auto& v : s.mesh().vertices) box.extend(v);
  return box;
}

void BM_NeckRead(benchmark::State& state) {
  if (!std::filesystem::exists(kNeck)) return state.SkipWithError("no shared neck mesh");
  for (auto _ : state) benchmark::DoNotOptimize(read_triangle_mesh(kNeck, 1.0));
}
BENCHMARK(BM_NeckRead)->Unit(benchmark::kMillisecond);

void BM_NeckIndex(benchmark::State& state) {
  if (!std::filesystem::exists(kNeck)) return state.SkipWithError("no shared neck mesh");
  const TriangleMesh mesh = read_triangle_mesh(kNeck, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(SurfaceMesh(mesh));  // adjacency, normals, AABB tree
}
BENCHMARK(BM_NeckIndex)->Unit(benchmark::kMillisecond);

// Random query points in the bounding box grown by 2 cm.
void BM_NeckClosestPoint(benchmark::State& state) {
  const SurfaceMesh* s = neck();
  if (!s) return state.SkipWithError("no shared neck mesh");
  Eigen::AlignedBox3d box = box_of(*s);
  box.extend(box.min() - Eigen::Vector3d::Constant(0.02)).extend(box.max() + Eigen::Vector3d::Constant(0.02));
  std::vector<Eigen::Vector3d> points(4096);
  for (auto& p : points) p = box.sample();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s->closest_point(points[i++ % points.size()]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NeckClosestPoint);

// Points 0-5 mm off the skin near the anterior neck, as a patch's nodes would be.
void BM_NeckClosestPointNearSkin(benchmark::State& state) {
  const SurfaceMesh* s = neck();
  if (!s) return state.SkipWithError("no shared neck mesh");
  const Eigen::Vector3d centre = s->mesh().vertices[kAnteriorNeck];
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  std::vector<Eigen::Vector3d> points(4096);
  for (auto& p : points) p = centre + Eigen::Vector3d(u(rng), u(rng), 0.5 * std::abs(u(rng)));
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s->closest_point(points[i++ % points.size()]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NeckClosestPointNearSkin);

// Rays along -Z from 10 cm in front of the neck over a 2 x 2 cm window (a rigid patch lowered onto the skin).
void BM_NeckFirstHit(benchmark::State& state) {
  const SurfaceMesh* s = neck();
  if (!s) return state.SkipWithError("no shared neck mesh");
  const Eigen::Vector3d centre = s->mesh().vertices[kAnteriorNeck];
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  std::vector<Eigen::Vector3d> origins(4096);
  for (auto& p : origins) p = centre + Eigen::Vector3d(u(rng), u(rng), 0.1);
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    const auto hit = s->first_hit(origins[i++ % origins.size()], -Eigen::Vector3d::UnitZ());
    hits += hit.has_value();
    benchmark::DoNotOptimize(hit);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_NeckFirstHit);

// 5 mm traces from the anterior neck in 16 directions (a 10 x 10 mm patch's springs).
template <bool Cutting>
void BM_NeckTrace5mm(benchmark::State& state) {
  const SurfaceMesh* s = neck();
  if (!s) return state.SkipWithError("no shared neck mesh");
  const auto start =
      surface_location(s->closest_point(s->mesh().vertices[kAnteriorNeck] + Eigen::Vector3d(1e-4, 2e-4, 0)));
  int k = 0;
  for (auto _ : state) {
    const double a = 0.3927 * (k++ % 16);
    const Eigen::Vector3d d(std::cos(a), std::sin(a), 0);
    benchmark::DoNotOptimize(Cutting ? cutting_plane_trace(*s, start, d, 5e-3)
                                     : straightest_geodesic(*s, start, d, 5e-3));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NeckTrace5mm<false>)->Name("BM_NeckStraightestGeodesic5mm");
BENCHMARK(BM_NeckTrace5mm<true>)->Name("BM_NeckCuttingPlaneTrace5mm");

// Geodesic distance between points 1-8 mm apart on the anterior neck.
void BM_NeckGeodesicDistance(benchmark::State& state) {
  const SurfaceMesh* s = neck();
  if (!s) return state.SkipWithError("no shared neck mesh");
  const Eigen::Vector3d centre = s->mesh().vertices[kAnteriorNeck];
  const auto from = surface_location(s->closest_point(centre));
  std::vector<SurfaceLocation> targets;
  for (int k = 0; k < 16; ++k) {
    const double a = 0.7 * k, r = 1e-3 * (1 + k % 8);
    targets.push_back(surface_location(s->closest_point(centre + r * Eigen::Vector3d(std::cos(a), std::sin(a), 0))));
  }
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(geodesic_distance(*s, from, targets[i++ % targets.size()]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NeckGeodesicDistance);

}  // namespace
