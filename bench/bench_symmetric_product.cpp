// The tangent's symmetric product (src/fem/symmetric_product.hpp) alone, on the pattern of linear tetrahedra on a
// structured block (argument: cells per side; 24: 83k tets, 47k free dofs), nodes in the solver's Morton order,
// random entries. CG and the two-grid smoother spend most of a solve in it.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <numeric>
#include <random>

#include "../src/fem/boundary_conditions.hpp"
#include "../src/fem/morton_order.hpp"
#include "../src/fem/sparse_pattern.hpp"
#include "../src/fem/symmetric_product.hpp"
#include "needlekit/mesh/structured_block_mesh.hpp"

using namespace needlekit;

namespace {

void BM_SymmetricProduct(benchmark::State& state) {
  mesh::StructuredBlockOptions o;
  o.width = o.length = 1e-3, o.height = 0.5e-3;
  o.nx = o.ny = static_cast<int>(state.range(0)), o.nz = o.nx / 2;
  const mesh::TetMesh block = mesh::structured_block_mesh(o);
  std::vector<int> connectivity;
  for (const auto& t : block.tets) connectivity.insert(connectivity.end(), t.begin(), t.end());
  Eigen::Vector3d low = block.nodes.front(), high = low;
  for (const auto& p : block.nodes) low = low.cwiseMin(p), high = high.cwiseMax(p);
  std::vector<char> fixed(3 * block.nodes.size(), 0);
  for (size_t n = 0; n < block.nodes.size(); ++n)
    if (block.nodes[n].z() < low.z() + 1e-9) fixed[3 * n] = fixed[3 * n + 1] = fixed[3 * n + 2] = 1;
  const fem::detail::DofMap dofs = fem::detail::dof_map(fixed, {}, fem::detail::morton_order(block.nodes, low, high));
  const fem::detail::UpperPattern pattern =
      fem::detail::upper_pattern(connectivity, 4, static_cast<int>(block.nodes.size()), dofs.free_index);
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
