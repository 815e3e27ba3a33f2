#include "nodal_volume_preconditioner.hpp"

namespace needlekit::fem::detail {

NodalVolumePreconditioner::NodalVolumePreconditioner(const TangentInputs& inputs, const UpperPattern& one_ring,
                                                     SymmetricProduct& product, tbb::task_arena& arena)
    : free_index_(inputs.free_index),
      nodal_(*inputs.nodal),
      arena_(arena),
      product_(product),
      two_grid_(inputs, one_ring, arena),
      multiply_a_([this](const Eigen::VectorXd& x, Eigen::VectorXd& y) { product_.multiply(*a_values_, x, y); }) {}

bool NodalVolumePreconditioner::update(const std::vector<double>& a_values) {
  a_values_ = &a_values;
  return two_grid_.update(a_values, multiply_a_);
}

void NodalVolumePreconditioner::refresh_smoother(const std::vector<double>& a_values) {
  a_values_ = &a_values;
  two_grid_.set_smoother_diagonal(a_values);
}

void NodalVolumePreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  two_grid_.apply(r, cycled_, multiply_a_);                                        // B r
  nodal_.gradient_transpose_product(free_index_, cycled_, nodal_values_, arena_);  // G^T B r
  for (Eigen::Index a = 0; a < nodal_values_.size(); ++a)                          // Ŝ^-1 G^T B r
    nodal_values_[a] *= nodal_.inverse_schur_diagonal(static_cast<size_t>(a));
  spread_.setZero(r.size());
  nodal_.add_gradient_product(free_index_, nodal_values_, spread_, arena_);  // G Ŝ^-1 G^T B r
  two_grid_.apply(spread_, correction_, multiply_a_);
  z = cycled_ - correction_;
}

}  // namespace needlekit::fem::detail
