// Internal: a two-grid preconditioner for the free-dof stiffness K of a mesh with a coarse level
// (mesh::CoarseLevel: a split mesh's parent, the corner nodes of quadratic tetrahedra, or the body meshed again at
// three times the sizes).
//
//   B r = S r + (I - S K) P A_c^-1 P^T (I - K S) r     (symmetric V(1,1) cycle; Trottenberg et al., Multigrid, §2.4)
//
// P interpolates coarse displacements linearly (the coarse level's weights: 1 at a coarse node, 1/2 and 1/2 at an
// edge midpoint, barycentric coordinates in a non-nested coarse mesh), the coarse operator is Galerkin's
// A_c = P^T K P (exact for the coarse level whatever the material jumps or constraints of the fine one, and for
// non-nested meshes the usual choice: Chan, Smith & Zou 1996, "Overlapping Schwarz methods on unstructured meshes
// using non-matching coarse grids", Numer Math 73), factorized by CHOLMOD, and the smoother S is a Chebyshev polynomial
// in D^-1 K (D = diag K) on [lambda_max / 10, 1.1 lambda_max] (Adams, Brezina, Hu, Tuminaro 2003, "Parallel multigrid
// smoothing: polynomial versus Gauss-Seidel", J Comput Phys 188), threaded through K's product alone.
//
// Why written here: Debian's algebraic multigrid (hypre, PETSc GAMG, Trilinos ML/MueLu) comes inside MPI stacks
// that must own the process; the geometric hierarchy makes a two-level method a few hundred lines.
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "needlekit/mesh/coarse_level.hpp"
#include "sparse_pattern.hpp"
#include "tangent_inputs.hpp"

namespace needlekit::fem::detail {

class SparseCholesky;

class TwoGridPreconditioner {
public:
  using Multiply = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;  // y = K x

  // `fine`: the pattern of K over the fine free dofs; of `inputs`, the coarse level (required), the free-dof numbering
  // and the fine elements (connectivity, nodes_per_element). A coarse dof is kept when more than half of its
  // interpolation weight goes to free fine dofs; A_c's pattern couples the coarse nodes interpolated by one fine
  // element. The coarse operator's assembly runs in `arena` (the solver's threads).
  TwoGridPreconditioner(const TangentInputs& inputs, const UpperPattern& fine, tbb::task_arena& arena,
                        int chebyshev_degree = 4);
  ~TwoGridPreconditioner();
  TwoGridPreconditioner(const TwoGridPreconditioner&) = delete;
  TwoGridPreconditioner& operator=(const TwoGridPreconditioner&) = delete;

  // Rebuilds the coarse operator from K's values and factorizes it, and bounds the smoother's spectrum. False if
  // the coarse operator is not positive definite.
  bool update(const std::vector<double>& values, const Multiply& multiply);
  // The smoother's diagonal D from K's values; update() sets it too. Call it when K changed but the coarse operator
  // is kept.
  void set_smoother_diagonal(const std::vector<double>& values);
  // z = B r with the current K (`multiply` its product; the smoother's diagonal as last set).
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z, const Multiply& multiply);

  int coarse_dofs() const;
  double coarse_factor_nonzeros() const;
  double coarse_factor_flops() const;

private:
  // The construction's steps: the coarse dofs kept and the interpolation rows (returns the coarse free dofs), the
  // restriction's table per coarse dof, and the coupled dofs per fine dof (the Galerkin product's tables).
  int build_interpolation(const TangentInputs& inputs);
  void build_restriction(int coarse_count);
  void build_neighbours();
  // Chebyshev smoothing of K x = r from x = 0.
  void smooth(const Eigen::VectorXd& r, Eigen::VectorXd& x, const Multiply& multiply);

  struct Interpolation {  // one fine free dof: its coarse free dofs (-1: none) and weights
    std::array<int, 4> coarse{-1, -1, -1, -1};
    std::array<double, 4> weight{0, 0, 0, 0};
  };
  std::vector<Interpolation> interpolation_;  // per fine free dof
  std::vector<int> coarse_free_;              // per coarse dof: its coarse free dof, -1 when left out
  struct Restriction {  // one fine free dof that a coarse dof interpolates, with its weight
    int32_t fine;
    double weight;
  };
  std::vector<int32_t> restriction_pointers_;  // per coarse free dof (+1) into restriction_
  std::vector<Restriction> restriction_;
  struct Neighbour {  // a fine free dof coupled to another and the index of their stored entry in K
    int32_t dof;
    int32_t entry;
  };
  std::vector<int64_t> neighbour_pointers_;  // per fine free dof (+1) into neighbours_: K's column and row
  std::vector<Neighbour> neighbours_;
  const UpperPattern& fine_;
  tbb::task_arena& arena_;
  UpperPattern coarse_pattern_;
  std::vector<double> coarse_values_;
  std::unique_ptr<SparseCholesky> coarse_cholesky_;
  int degree_;
  double lambda_max_ = 0;                   // of D^-1 K at the last update
  Eigen::VectorXd inverse_diagonal_, residual_, smoother_residual_, direction_, product_, correction_;
};

}  // namespace needlekit::fem::detail
