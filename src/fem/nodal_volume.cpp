#include "nodal_volume.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <cmath>

namespace needlekit::fem::detail {
namespace {

// Position of `node` in the sorted patch [first, last); the node must be there.
int patch_position(const int* first, const int* last, int node) {
  return static_cast<int>(std::lower_bound(first, last, node) - first);
}

// Sums a per-item value over fixed blocks, then the blocks in order: the same result for any number of threads.
template <class F>
double deterministic_sum(size_t n, tbb::task_arena& arena, F&& value) {
  constexpr size_t kBlock = 1024;
  std::vector<double> block((n + kBlock - 1) / kBlock, 0.0);
  arena.execute([&] {
    tbb::parallel_for(size_t{0}, block.size(), [&](size_t b) {
      double s = 0;
      for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) s += value(i);
      block[b] = s;
    });
  });
  double total = 0;
  for (double s : block) total += s;
  return total;
}

}  // namespace

NodalVolumeAverage::NodalVolumeAverage(FunctionSpace& space, const std::vector<char>& treated,
                                       double stabilization)
    : space_(space), treated_(treated), stabilization_(stabilization) {
  const size_t ne = space.elements.size(), nnode = space.nodes.size();
  element_j_.assign(ne, 1.0);
  element_pressure_.assign(ne, 0.0);
  element_jh_.assign(ne, Eigen::Matrix<double, 3, 4>::Zero());
  node_volume_.assign(nnode, 0.0);
  node_lambda_.assign(nnode, 0.0);
  node_compliance_.assign(nnode, 0.0);
  std::vector<int> count(nnode + 1, 0);
  for (size_t e = 0; e < ne; ++e) {
    if (!treated_[e]) continue;
    ++element_count_;
    for (int a = 0; a < 4; ++a) {
      const int n = space.connectivity[4 * e + a];
      count[static_cast<size_t>(n) + 1]++;
      node_volume_[n] += space.volumes[e] / 4;
      node_lambda_[n] += (space.lame[e].lambda - element_lambda(space.lame[e])) * space.volumes[e] / 4;
      node_compliance_[n] += space.volumes[e] / 4 / (element_lambda(space.lame[e]) + 2 * space.lame[e].mu / 3);
    }
  }
  for (size_t n = 0; n < nnode; ++n) {
    if (node_volume_[n] > 0) node_lambda_[n] /= node_volume_[n];
    count[n + 1] += count[n];
  }
  node_element_pointers_ = count;
  node_elements_.resize(static_cast<size_t>(count.back()));
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (size_t e = 0; e < ne; ++e)
    if (treated_[e])
      for (int a = 0; a < 4; ++a) node_elements_[static_cast<size_t>(fill[space.connectivity[4 * e + a]]++)] = static_cast<int>(e);
  for (size_t e = 0; e < ne; ++e)
    if (treated_[e]) space.lame[e].lambda = element_lambda(space.lame[e]);  // the element part keeps μ and λ_s
  // Patches: the nodes of the treated elements around each node.
  patch_pointers_.assign(nnode + 1, 0);
  for (size_t n = 0; n < nnode; ++n) {
    std::vector<int> patch;
    for (int k = node_element_pointers_[n]; k < node_element_pointers_[n + 1]; ++k)
      for (int a = 0; a < 4; ++a) patch.push_back(space.connectivity[4 * static_cast<size_t>(node_elements_[k]) + a]);
    std::sort(patch.begin(), patch.end());
    patch.erase(std::unique(patch.begin(), patch.end()), patch.end());
    patch_nodes_.insert(patch_nodes_.end(), patch.begin(), patch.end());
    patch_pointers_[n + 1] = static_cast<int>(patch_nodes_.size());
  }
  node_curvature_.assign(nnode, 0.0);
  patch_gradient_.assign(patch_nodes_.size(), Eigen::Vector3d::Zero());
  patch_transpose_.resize(patch_nodes_.size());
  for (size_t a = 0; a < nnode; ++a)  // b is in a's patch exactly when a is in b's (they share an element)
    for (int k = patch_pointers_[a]; k < patch_pointers_[a + 1]; ++k) {
      const size_t b = static_cast<size_t>(patch_nodes_[static_cast<size_t>(k)]);
      const int* first = &patch_nodes_[0] + patch_pointers_[b];
      patch_transpose_[static_cast<size_t>(k)] =
          patch_pointers_[b] + patch_position(first, &patch_nodes_[0] + patch_pointers_[b + 1], static_cast<int>(a));
    }
}

double NodalVolumeAverage::element_lambda(const LameConstants& lame) const {
  return std::min(lame.lambda, stabilization_ * lame.mu);
}

double NodalVolumeAverage::node_volume_ratio(size_t n) const {
  double v = 0;
  for (int k = node_element_pointers_[n]; k < node_element_pointers_[n + 1]; ++k) {
    const size_t e = static_cast<size_t>(node_elements_[k]);
    v += element_j_[e] * space_.volumes[e] / 4;
  }
  return v / node_volume_[n];
}

bool NodalVolumeAverage::update(const Eigen::VectorXd& u, bool with_tangent, double& energy, tbb::task_arena& arena) {
  const size_t ne = space_.elements.size(), nnode = space_.nodes.size();
  inverted_element_ = -1;
  std::atomic<bool> valid{true};
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 1024), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t e = r.begin(); e < r.end(); ++e) {
        if (!treated_[e]) continue;
        const Eigen::Map<const Eigen::Matrix<double, 3, 4>> g(&space_.gradients[12 * e]);
        Eigen::Matrix<double, 3, 4> ue;
        for (int a = 0; a < 4; ++a) ue.col(a) = u.segment<3>(3 * space_.connectivity[4 * e + a]);
        const Eigen::Matrix3d f = space_.initial(e) + ue * g.transpose();
        const double j = f.determinant();
        element_j_[e] = j;
        if (!(j > 0)) {
          valid = false;
          continue;
        }
        element_jh_[e] = j * f.inverse().transpose() * g;  // J h_b = J F^-T ∇N_b = ∂J/∂u_b
      }
    });
  });
  if (!valid) {
    for (size_t e = 0; e < ne && inverted_element_ < 0; ++e)
      if (treated_[e] && !(element_j_[e] > 0)) inverted_element_ = static_cast<int>(e);
    return false;
  }
  // Nodal volume ratios, energies, pressures U'(J̄) and curvatures U''(J̄)/V_a, with U = λ/2 (ln J)^2.
  std::vector<double> node_pressure(nnode, 0.0);
  energy = deterministic_sum(nnode, arena, [&](size_t n) {
    if (node_volume_[n] <= 0) return 0.0;
    const double j = node_volume_ratio(n);
    if (!(j > 0)) {
      valid = false;
      return 0.0;
    }
    const double lambda = node_lambda_[n], lnj = std::log(j);
    node_pressure[n] = lambda * lnj / j;
    node_curvature_[n] = lambda * (1 - lnj) / (j * j) / node_volume_[n];
    return node_volume_[n] * 0.5 * lambda * lnj * lnj;
  });
  if (!valid) {
    for (size_t n = 0; n < nnode && inverted_element_ < 0; ++n)
      if (node_volume_[n] > 0 && !(node_volume_ratio(n) > 0)) inverted_element_ = node_elements_[node_element_pointers_[n]];
    return false;
  }
  for (size_t e = 0; e < ne; ++e) {
    if (!treated_[e]) continue;
    const int* c = &space_.connectivity[4 * e];
    element_pressure_[e] = 0.25 * (node_pressure[c[0]] + node_pressure[c[1]] + node_pressure[c[2]] + node_pressure[c[3]]);
  }
  if (!with_tangent) return true;
  // g_a over the patch of each node (each node's own entries: no two tasks write the same place).
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nnode, 256), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t n = r.begin(); n < r.end(); ++n) {
        const int* first = &patch_nodes_[0] + patch_pointers_[n];
        const int* last = &patch_nodes_[0] + patch_pointers_[n + 1];
        Eigen::Vector3d* gn = &patch_gradient_[static_cast<size_t>(patch_pointers_[n])];
        for (const int* p = first; p != last; ++p) gn[p - first].setZero();
        for (int k = node_element_pointers_[n]; k < node_element_pointers_[n + 1]; ++k) {
          const size_t e = static_cast<size_t>(node_elements_[k]);
          for (int b = 0; b < 4; ++b)
            gn[patch_position(first, last, space_.connectivity[4 * e + b])] += space_.volumes[e] / 4 * element_jh_[e].col(b);
        }
      }
    });
  });
  return true;
}

double NodalVolumeAverage::element_bulk_curvature(int element) const {
  const int* c = &space_.connectivity[4 * static_cast<size_t>(element)];
  double sum = 0;
  for (int a = 0; a < 4; ++a) sum += std::max(0.0, node_curvature_[c[a]] * node_volume_[c[a]]);
  return sum / 4;
}

void NodalVolumeAverage::add_patch_tangent(const std::vector<int>& free_index, const UpperPattern& pattern,
                                           std::vector<double>& values, tbb::task_arena& arena) const {
  const size_t nnode = space_.nodes.size();
  const size_t free_count = pattern.column_pointers.size() - 1;
  tbb::enumerable_thread_specific<std::vector<int64_t>> scatter([&] { return std::vector<int64_t>(free_count, -1); });
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nnode, 64), [&](const tbb::blocked_range<size_t>& r) {
      std::vector<int64_t>& position = scatter.local();
      for (size_t c = r.begin(); c < r.end(); ++c) {
        const int* cfirst = &patch_nodes_[0] + patch_pointers_[c];
        const int* clast = &patch_nodes_[0] + patch_pointers_[c + 1];
        for (int j = 0; j < 3; ++j) {
          const int column = free_index[3 * c + j];
          if (column < 0) continue;
          for (int64_t k = pattern.column_pointers[column]; k < pattern.column_pointers[column + 1]; ++k)
            position[static_cast<size_t>(pattern.row_indices[k])] = k;
          for (const int* pa = cfirst; pa != clast; ++pa) {  // the nodes a whose patch holds c
            const size_t a = static_cast<size_t>(*pa);
            const int* first = &patch_nodes_[0] + patch_pointers_[a];
            const int* last = &patch_nodes_[0] + patch_pointers_[a + 1];
            const Eigen::Vector3d* ga = &patch_gradient_[static_cast<size_t>(patch_pointers_[a])];
            const double kc = node_curvature_[a] * ga[patch_position(first, last, static_cast<int>(c))][j];
            if (kc == 0) continue;
            for (const int* pb = first; pb != last; ++pb)
              for (int i = 0; i < 3; ++i) {
                const int row = free_index[3 * static_cast<size_t>(*pb) + i];
                if (row < 0 || row > column) continue;
                values[static_cast<size_t>(position[static_cast<size_t>(row)])] += kc * ga[pb - first][i];
              }
          }
          for (int64_t k = pattern.column_pointers[column]; k < pattern.column_pointers[column + 1]; ++k)
            position[static_cast<size_t>(pattern.row_indices[k])] = -1;
        }
      }
    });
  });
}

double NodalVolumeAverage::inverse_schur_diagonal(size_t node) const {
  const double d = std::max(0.0, node_curvature_[node]);
  return d / (1 + d * node_compliance_[node]);
}

void NodalVolumeAverage::gradient_transpose_product(const std::vector<int>& free_index, const Eigen::VectorXd& x,
                                                    Eigen::VectorXd& q, tbb::task_arena& arena) const {
  const size_t nnode = node_volume_.size();
  q.resize(static_cast<Eigen::Index>(nnode));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nnode, 512), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t a = r.begin(); a < r.end(); ++a) {
        double s = 0;
        for (int k = patch_pointers_[a]; k < patch_pointers_[a + 1]; ++k)
          for (int i = 0; i < 3; ++i) {
            const int row = free_index[3 * static_cast<size_t>(patch_nodes_[static_cast<size_t>(k)]) + i];
            if (row >= 0) s += patch_gradient_[static_cast<size_t>(k)][i] * x[row];
          }
        q[static_cast<Eigen::Index>(a)] = s;
      }
    });
  });
}

void NodalVolumeAverage::add_gradient_product(const std::vector<int>& free_index, const Eigen::VectorXd& q,
                                              Eigen::VectorXd& y, tbb::task_arena& arena) const {
  const size_t nnode = node_volume_.size();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nnode, 512), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t b = r.begin(); b < r.end(); ++b) {  // y at node b: Σ over the nodes a of its patch of q_a g_a(b)
        Eigen::Vector3d s = Eigen::Vector3d::Zero();
        for (int k = patch_pointers_[b]; k < patch_pointers_[b + 1]; ++k)
          s += q[patch_nodes_[static_cast<size_t>(k)]] *
               patch_gradient_[static_cast<size_t>(patch_transpose_[static_cast<size_t>(k)])];
        for (int i = 0; i < 3; ++i) {
          const int row = free_index[3 * b + i];
          if (row >= 0) y[row] += s[i];
        }
      }
    });
  });
}

void NodalVolumeAverage::add_patch_tangent(const std::vector<int>& free_index,
                                           const std::vector<Eigen::Index>& position, Eigen::MatrixXd& dense) const {
  for (size_t a = 0; a + 1 < patch_pointers_.size(); ++a)
    for (int k = patch_pointers_[a]; k < patch_pointers_[a + 1]; ++k)
      for (int l = patch_pointers_[a]; l < patch_pointers_[a + 1]; ++l)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int row = free_index[static_cast<size_t>(3 * patch_nodes_[static_cast<size_t>(k)] + i)];
            const int column = free_index[static_cast<size_t>(3 * patch_nodes_[static_cast<size_t>(l)] + j)];
            if (row < 0 || column < 0) continue;
            dense(position[static_cast<size_t>(row)], position[static_cast<size_t>(column)]) +=
                node_curvature_[a] * patch_gradient_[static_cast<size_t>(k)][i] *
                patch_gradient_[static_cast<size_t>(l)][j];
          }
}

void NodalVolumeAverage::add_prescribed_coupling(const std::vector<int>& free_index, const Eigen::VectorXd& dup,
                                                 Eigen::VectorXd& kdup) const {
  for (size_t a = 0; a + 1 < patch_pointers_.size(); ++a) {
    if (node_curvature_[a] == 0) continue;
    double s = 0;  // g_a . dup over the prescribed dofs
    for (int k = patch_pointers_[a]; k < patch_pointers_[a + 1]; ++k)
      for (int i = 0; i < 3; ++i) {
        const int dof = 3 * patch_nodes_[static_cast<size_t>(k)] + i;
        if (free_index[static_cast<size_t>(dof)] < 0) s += patch_gradient_[static_cast<size_t>(k)][i] * dup[dof];
      }
    if (s == 0) continue;
    for (int k = patch_pointers_[a]; k < patch_pointers_[a + 1]; ++k)
      for (int i = 0; i < 3; ++i) {
        const int row = free_index[static_cast<size_t>(3 * patch_nodes_[static_cast<size_t>(k)] + i)];
        if (row >= 0) kdup[row] += node_curvature_[a] * patch_gradient_[static_cast<size_t>(k)][i] * s;
      }
  }
}

}  // namespace needlekit::fem::detail
