// Internal: a preconditioner for the tangent of the nodal-averaged tetrahedron (nodal_volume.hpp) that needs no
// factor of the fine mesh.
//
// The tangent is K = A + G D G^T: A the one-ring element part (μ, the element's own bulk share λ_s and the pressure's
// geometric term), G the nodal volume gradients, D = diag(U_a'' / V_a) of the nodal bulk term. K is the Schur
// complement of the displacement-pressure system [[A, G], [G^T, -D^-1]] with one pressure per node, and by
// Sherman-Morrison-Woodbury
//     K^-1 = A^-1 - A^-1 G (D^-1 + G^T A^-1 G)^-1 G^T A^-1.
// The preconditioner takes A^-1 ≈ B, the two-grid cycle on A (two_grid_preconditioner.hpp: A is compressible
// elasticity of about ν = 0.25, where the cycle works), and the Schur complement ≈ its diagonal upper bound Ŝ of
// NodalVolumeAverage::inverse_schur_diagonal:
//     M^-1 r = B r - B G Ŝ^-1 G^T B r
// (the block-triangular factorization of the u-p system's inverse; Benzi, Golub & Liesen 2005, "Numerical solution
// of saddle point problems", Acta Numerica 14, 1-137, on block preconditioners). M^-1 is symmetric, and positive
// definite when Ŝ bounds G^T B G from above, which the bound on G^T A^-1 G gives for a cycle with B <= A^-1. Two
// cycles per application; no fine factorization (the split preconditioner's one-ring factor of the §6.2 sharp bevel
// has 1.9e8 entries).
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "nodal_volume.hpp"
#include "sparse_pattern.hpp"
#include "symmetric_product.hpp"
#include "two_grid_preconditioner.hpp"

namespace needlekit::fem::detail {

class NodalVolumePreconditioner {
public:
  // `one_ring`: A's pattern over the free dofs and `product` the tangent's product on it (shared: one set of
  // partial sums); of `inputs`, the coarse level and the nodal average (both required; the volume average whose G
  // and D the tangent holds), the free-dof numbering and the linear elements. All must outlive this object.
  NodalVolumePreconditioner(const TangentInputs& inputs, const UpperPattern& one_ring, SymmetricProduct& product,
                            tbb::task_arena& arena);

  // A's values on the one-ring pattern (kept by reference until the next update): rebuilds the coarse operator and
  // the smoother's bound. False if the coarse operator is not positive definite.
  bool update(const std::vector<double>& a_values);
  // A changed (a new Newton iteration) but the coarse operator is kept: the smoother's diagonal from A's values.
  void refresh_smoother(const std::vector<double>& a_values);
  // z = M^-1 r.
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z);

  double coarse_factor_nonzeros() const { return two_grid_.coarse_factor_nonzeros(); }
  double coarse_factor_flops() const { return two_grid_.coarse_factor_flops(); }

private:
  const std::vector<int>& free_index_;
  const NodalVolumeAverage& nodal_;
  tbb::task_arena& arena_;
  SymmetricProduct& product_;
  TwoGridPreconditioner two_grid_;
  const std::vector<double>* a_values_ = nullptr;
  TwoGridPreconditioner::Multiply multiply_a_;
  Eigen::VectorXd cycled_, nodal_values_, spread_, correction_;
};

}  // namespace needlekit::fem::detail
