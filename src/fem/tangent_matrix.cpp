#include "tangent_matrix.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>

#include "needlekit/core/errors.hpp"

namespace needlekit::fem::detail {

TangentMatrix::TangentMatrix(const TangentInputs& in, const TangentLayout& layout, tbb::task_arena& arena)
    : arena_(arena), free_index_(in.free_index) {
  if (in.nodal && layout.patch_term_in_product) patch_term_ = in.nodal;
  const bool two_ring = in.nodal && !patch_term_;
  pattern_ = upper_pattern(in.connectivity, in.nodes_per_element, in.node_count, in.free_index,
                           two_ring ? &in.nodal->patch_pointers() : nullptr,
                           two_ring ? &in.nodal->patch_nodes() : nullptr);
  values_.assign(pattern_.row_indices.size(), 0.0);
  if (values_.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    throw InvalidInput("tissue mesh: the stiffness matrix has " + std::to_string(values_.size()) +
                       " entries, more than this solver indexes");
  product_ = std::make_unique<SymmetricProduct>(pattern_, arena_);
  fill_element_slots(in);
  if (!in.nodal || !layout.one_ring_preconditioner) return;
  if (two_ring) {
    map_preconditioner_entries(in);
  } else {  // the patch term in the product: P on K's own one-ring pattern
    pre_pattern_ = pattern_;
    pre_values_.assign(values_.size(), 0.0);
    full_to_pre_.resize(values_.size());
    std::iota(full_to_pre_.begin(), full_to_pre_.end(), 0);
  }
}

void TangentMatrix::fill_element_slots(const TangentInputs& in) {
  const int nn = in.nodes_per_element;
  const int k = 3 * nn;
  const std::vector<int>& conn = in.connectivity;
  const size_t ne = conn.size() / static_cast<size_t>(nn);
  slots_per_element_ = static_cast<size_t>(upper_slots(k));
  value_slot_.assign(ne * slots_per_element_, -1);
  arena_.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 1024), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t position = range.begin(); position < range.end(); ++position) {
        const size_t e = static_cast<size_t>(in.assembly_order[position]);
        int32_t* slot = &value_slot_[position * slots_per_element_];
        for (int col = 0; col < k; ++col) {
          const int cb = free_index_[3 * conn[e * nn + col / 3] + col % 3];
          for (int row = 0; row <= col; ++row, ++slot) {
            const int ra = free_index_[3 * conn[e * nn + row / 3] + row % 3];
            if (ra < 0 || cb < 0) continue;
            *slot = static_cast<int32_t>(entry_position(pattern_, std::min(ra, cb), std::max(ra, cb)));
          }
        }
      }
    });
  });
}

void TangentMatrix::map_preconditioner_entries(const TangentInputs& in) {
  pre_pattern_ = upper_pattern(in.connectivity, in.nodes_per_element, in.node_count, in.free_index);
  pre_values_.assign(pre_pattern_.row_indices.size(), 0.0);
  full_to_pre_.assign(values_.size(), -1);
  for (int64_t c = 0; c < free_count(); ++c) {  // both patterns sorted per column, P's a subset of K's
    int64_t k = pattern_.column_pointers[static_cast<size_t>(c)];
    for (int64_t q = pre_pattern_.column_pointers[static_cast<size_t>(c)];
         q < pre_pattern_.column_pointers[static_cast<size_t>(c) + 1]; ++q) {
      while (pattern_.row_indices[static_cast<size_t>(k)] < pre_pattern_.row_indices[static_cast<size_t>(q)]) ++k;
      full_to_pre_[static_cast<size_t>(k)] = static_cast<int32_t>(q);
    }
  }
}

void TangentMatrix::capture_preconditioner() {
  for (size_t k = 0; k < values_.size(); ++k)
    if (full_to_pre_[k] >= 0) pre_values_[static_cast<size_t>(full_to_pre_[k])] = values_[k];
}

void TangentMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  product_->multiply(values_, x, y);
  if (patch_term_) add_patch_product(x, y);
}

void TangentMatrix::multiply(std::span<const Eigen::VectorXd* const> xs, std::span<Eigen::VectorXd* const> ys) {
  product_->multiply(values_, xs, ys);
  if (patch_term_)
    for (size_t i = 0; i < xs.size(); ++i) add_patch_product(*xs[i], *ys[i]);
}

void TangentMatrix::add_patch_product(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  patch_term_->gradient_transpose_product(free_index_, x, patch_values_, arena_);
  for (Eigen::Index a = 0; a < patch_values_.size(); ++a)
    patch_values_[a] *= patch_term_->node_curvature(static_cast<size_t>(a));
  patch_term_->add_gradient_product(free_index_, patch_values_, y, arena_);
}

}  // namespace needlekit::fem::detail
