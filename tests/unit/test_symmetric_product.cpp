// The tangent's symmetric product (internal fem::detail::SymmetricProduct): K x from the stored upper triangle equals
// the full symmetric matrix's product, several vectors at once give each bitwise its single product (Krylov
// recycling relies on it to leave the solves unchanged), and the result does not depend on the number of threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "../../src/fem/boundary_conditions.hpp"
#include "../../src/fem/sparse_pattern.hpp"
#include "../../src/fem/symmetric_product.hpp"
#include "../support/bottom_fixed_block.hpp"

using namespace needlekit;
using needlekit::fem::detail::SymmetricProduct;
using needlekit::fem::detail::UpperPattern;

namespace {

struct Problem {
  UpperPattern pattern;
  std::vector<double> values;
  Eigen::SparseMatrix<double> full;  // the symmetric matrix, both triangles
};

// The pattern of linear tetrahedra on a small block, the bottom face's nodes prescribed, random entries. With
// `tip_nodes`, every third node of the top face has its z prescribed by a needle tip (two free dofs, as under a
// flat tip).
Problem random_tangent(bool tip_nodes = false) {
  const test::BottomFixedBlock b = test::bottom_fixed_block(6, 6, 4);
  const int nodes = static_cast<int>(b.mesh.nodes.size());
  std::vector<int> identity(static_cast<size_t>(nodes));
  std::iota(identity.begin(), identity.end(), 0);
  double top = -1e300;
  for (const auto& x : b.mesh.nodes) top = std::max(top, x.z());
  std::vector<std::vector<int>> tips(1);
  for (int n = 0, on_top = 0; tip_nodes && n < nodes; ++n)
    if (b.mesh.nodes[static_cast<size_t>(n)].z() > top - 1e-9 && on_top++ % 3 == 0) tips[0].push_back(n);
  const fem::detail::DofMap dofs = fem::detail::dof_map(b.fixed, tips, identity);
  const int free = static_cast<int>(dofs.free_dofs.size());
  Problem p;
  p.pattern = fem::detail::upper_pattern(b.connectivity, 4, nodes, dofs.free_index);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  p.values.resize(p.pattern.row_indices.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int c = 0; c < free; ++c)
    for (int64_t k = p.pattern.column_pointers[static_cast<size_t>(c)];
         k < p.pattern.column_pointers[static_cast<size_t>(c) + 1]; ++k) {
      const int r = static_cast<int>(p.pattern.row_indices[static_cast<size_t>(k)]);
      const double v = p.values[static_cast<size_t>(k)] = u(rng);
      entries.emplace_back(r, c, v);
      if (r != c) entries.emplace_back(c, r, v);
    }
  p.full.resize(free, free);
  p.full.setFromTriplets(entries.begin(), entries.end());
  EXPECT_GT(free, 300) << "too few free dofs for the product's eight column ranges to matter";
  EXPECT_LT(free, 3 * nodes) << "no prescribed dofs";
  return p;
}

std::vector<Eigen::VectorXd> random_vectors(int count, Eigen::Index size) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::VectorXd> xs(static_cast<size_t>(count), Eigen::VectorXd(size));
  for (auto& x : xs)
    for (Eigen::Index i = 0; i < size; ++i) x[i] = u(rng);
  return xs;
}

}  // namespace

TEST(SymmetricProduct, EqualsTheFullMatrixProduct) {
  for (const bool tip_nodes : {false, true}) {
    const Problem p = random_tangent(tip_nodes);
    tbb::task_arena arena(2);
    SymmetricProduct product(p.pattern, arena);
    for (const Eigen::VectorXd& x : random_vectors(3, p.full.rows())) {
      Eigen::VectorXd y;
      product.multiply(p.values, x, y);
      const Eigen::VectorXd reference = p.full * x;
      EXPECT_LE((y - reference).norm(), 1e-13 * reference.norm()) << "tip nodes " << tip_nodes;
    }
    if (tip_nodes) EXPECT_EQ(p.full.rows() % 3, 1) << "17 of the 49 top nodes have two free dofs";
  }
}

TEST(SymmetricProduct, SeveralVectorsGiveEachBitwiseItsSingleProduct) {
  const Problem p = random_tangent();
  tbb::task_arena arena(2);
  SymmetricProduct product(p.pattern, arena);
  for (int count : {1, 3, 4, 7, 12}) {  // one partial pass, a full one, full ones plus the rest
    const std::vector<Eigen::VectorXd> xs = random_vectors(count, p.full.rows());
    std::vector<Eigen::VectorXd> ys(xs.size());
    std::vector<const Eigen::VectorXd*> in;
    std::vector<Eigen::VectorXd*> out;
    for (size_t i = 0; i < xs.size(); ++i) {
      in.push_back(&xs[i]);
      out.push_back(&ys[i]);
    }
    product.multiply(p.values, in, out);
    for (size_t i = 0; i < xs.size(); ++i) {
      Eigen::VectorXd single;
      product.multiply(p.values, xs[i], single);
      EXPECT_TRUE(ys[i] == single) << count << " vectors, vector " << i;
    }
  }
}

TEST(SymmetricProduct, IsBitwiseTheSameOnOneAndTwoThreads) {
  const Problem p = random_tangent();
  tbb::task_arena one(1), two(2);
  SymmetricProduct on_one(p.pattern, one), on_two(p.pattern, two);
  const Eigen::VectorXd x = random_vectors(1, p.full.rows()).front();
  Eigen::VectorXd y1, y2;
  on_one.multiply(p.values, x, y1);
  on_two.multiply(p.values, x, y2);
  EXPECT_TRUE(y1 == y2);
}
