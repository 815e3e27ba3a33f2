// The tangent's symmetric product (src/fem/symmetric_product.hpp) alone, on the pattern of linear tetrahedra on a
// structured block (argument: cells per side; 24: 41k tets, 22.5k free dofs), nodes in the solver's Morton order,
// random entries. CG and the two-grid smoother spend most of a solve in it.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <random>

#include "../src/fem/boundary_conditions.hpp"
#include "../src/fem/morton_order.hpp"
#include "../src/fem/sparse_pattern.hpp"
#include "../src/fem/symmetric_product.hpp"
#include "../tests/support/bottom_fixed_block.hpp"

using namespace needlekit;

namespace {

void BM_SymmetricProduct(benchmark::State& state) {
  const int cells = static_cast<int>(state.range(0));
  const test::BottomFixedBlock block = test::bottom_fixed_block(cells, cells, cells / 2);
  const std::vector<Eigen::Vector3d>& nodes = block.mesh.nodes;
  Eigen::Vector3d low = nodes.front(), high = low;
  for (const auto& p : nodes) low = low.cwiseMin(p), high = high.cwiseMax(p);
  const fem::detail::DofMap dofs = fem::detail::dof_map(block.fixed, {}, fem::detail::morton_order(nodes, low, high));
  const fem::detail::UpperPattern pattern =
      fem::detail::upper_pattern(block.connectivity, 4, static_cast<int>(nodes.size()), dofs.free_index);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> values(pattern.row_indices.size());
  for (double& v : values) v = u(rng);
  Eigen::VectorXd x(static_cast<Eigen::Index>(pattern.column_pointers.size() - 1)), y;
  for (double& v : x) v = u(rng);
  tbb::task_arena arena(2);
  fem::detail::SymmetricProduct product(pattern, arena);
  for (auto _ : state) {
    product.multiply(values, x, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["dofs"] = static_cast<double>(x.size());
  state.counters["entries"] = static_cast<double>(values.size());
}
BENCHMARK(BM_SymmetricProduct)->Arg(12)->Arg(24)->Arg(40)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
