// The element kernel (src/fem/tet_kernel.hpp) alone: energy, internal force and tangent of one tetrahedron under a
// moderate random deformation, through the public element_response. Arguments: nodes (4 or 10), law (0 SVK, 1
// neo-Hookean). The assembly of every Newton iteration runs it once per element.
#include <benchmark/benchmark.h>

#include <random>

#include "needlekit/fem/tet_element.hpp"

using namespace needlekit;

namespace {

void BM_ElementTangent(benchmark::State& state) {
  const int nodes = static_cast<int>(state.range(0));
  const auto law = state.range(1) ? fem::MaterialLaw::NeoHookean : fem::MaterialLaw::StVenantKirchhoff;
  std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {1e-4, 0, 0}, {0, 1e-4, 0}, {0, 0, 1e-4}};
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  if (nodes == 10)
    for (const auto& e : edges) x.push_back(0.5 * (x[e[0]] + x[e[1]]));
  const fem::ElementGeometry geometry = fem::element_geometry(x);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-5e-6, 5e-6);
  Eigen::VectorXd u(3 * nodes);
  for (auto& v : u) v = jitter(rng);
  const auto lame = fem::lame_constants(0.2e6, 0.49);
  for (auto _ : state) benchmark::DoNotOptimize(fem::element_response(geometry, law, lame, u, true));
}
BENCHMARK(BM_ElementTangent)->ArgsProduct({{4, 10}, {0, 1}});

}  // namespace
