#include "needlekit/patch/equilibrium_fit.hpp"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"
#include "needlekit/patch/fit_parameters.hpp"
#include "needlekit/patch/rigid_fit.hpp"

namespace needlekit::patch {
namespace {

struct Model {
  const geometry::SurfaceMesh& surface;
  const PatchDesign& design;
  const PatchFrame& frame;
  const std::vector<Eigen::Vector3d>& anchor;
  double load, contact, tangential;
};

double max_stiffness(const PatchDesign& design) {
  double k = 0;
  for (const Spring& s : design.springs) k = std::max(k, s.stiffness);
  return k;
}

// Signed gap of a point (negative inside) and the outward normal there.
std::pair<double, Eigen::Vector3d> gap(const geometry::SurfaceMesh& surface, const Eigen::Vector3d& x) {
  // The gap's gradient: the unit vector from the closest point (the face normal when the point is on the surface).
  const geometry::ClosestPoint cp = surface.closest_point(x);
  const Eigen::Vector3d face = surface.face_normal(cp.triangle);
  const Eigen::Vector3d offset = x - cp.point;
  const double side = offset.dot(face);
  const double distance = offset.norm();
  if (distance <= 1e-14) return {0.0, face};
  const Eigen::Vector3d n = side >= 0 ? Eigen::Vector3d(offset / distance) : Eigen::Vector3d(-offset / distance);
  return {side >= 0 ? distance : -distance, n};
}

double potential(const Model& m, const std::vector<Eigen::Vector3d>& x) {
  double total = 0;
  for (const Spring& s : m.design.springs) {
    const double stretch = (x[s.b] - x[s.a]).norm() - s.rest_length;
    total += 0.5 * s.stiffness * stretch * stretch;  // Eq 5.13
  }
  const Eigen::Vector3d& a = m.frame.approach;
  for (std::size_t k = 0; k < x.size(); ++k) {
    total -= m.load * a.dot(x[k]);
    const double g = gap(m.surface, x[k]).first;
    if (g < 0) total += 0.5 * m.contact * g * g;
    const Eigen::Vector3d d = x[k] - m.anchor[k];
    total += 0.5 * m.tangential * (std::pow(d.dot(m.frame.u), 2) + std::pow(d.dot(m.frame.v), 2));
  }
  return total;
}

// Gradient and a positive semi-definite Hessian approximation.
void gradient_and_hessian(const Model& m, const std::vector<Eigen::Vector3d>& x, Eigen::VectorXd& g,
                          Eigen::SparseMatrix<double>& H) {
  const int n = static_cast<int>(x.size());
  g.setZero(3 * n);
  std::vector<Eigen::Triplet<double>> triplets;
  auto add_block = [&](int r, int c, const Eigen::Matrix3d& block) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (block(i, j) != 0) triplets.emplace_back(3 * r + i, 3 * c + j, block(i, j));
  };
  for (const Spring& s : m.design.springs) {
    const Eigen::Vector3d d = x[s.b] - x[s.a];
    const double l = std::max(d.norm(), 1e-12 * s.rest_length);
    const Eigen::Vector3d e = d / l;
    const Eigen::Vector3d f = s.stiffness * (l - s.rest_length) * e;
    g.segment<3>(3 * s.b) += f;
    g.segment<3>(3 * s.a) -= f;
    // K = k·e eᵀ + k·(1 − L0/l)·(I − e eᵀ), the transverse part clamped at zero (compressed springs).
    const Eigen::Matrix3d ee = e * e.transpose();
    const Eigen::Matrix3d K =
        s.stiffness * ee + s.stiffness * std::max(0.0, 1 - s.rest_length / l) * (Eigen::Matrix3d::Identity() - ee);
    add_block(s.a, s.a, K);
    add_block(s.b, s.b, K);
    add_block(s.a, s.b, -K);
    add_block(s.b, s.a, -K);
  }
  const Eigen::Vector3d& a = m.frame.approach;
  const Eigen::Matrix3d P = m.frame.u * m.frame.u.transpose() + m.frame.v * m.frame.v.transpose();
  for (int k = 0; k < n; ++k) {
    g.segment<3>(3 * k) -= m.load * a;
    const auto [gk, normal] = gap(m.surface, x[k]);
    if (gk < 0) {
      g.segment<3>(3 * k) += m.contact * gk * normal;
      add_block(k, k, m.contact * normal * normal.transpose());
    }
    g.segment<3>(3 * k) += m.tangential * P * (x[k] - m.anchor[k]);
    add_block(k, k, m.tangential * P);
  }
  H.resize(3 * n, 3 * n);
  H.setFromTriplets(triplets.begin(), triplets.end());
}

// options.progress after each iteration: the larger of the share of max_iterations used and the decades of |grad|inf
// reduced from the first iterate's towards the tolerance (the patch first comes down in trust-region steps with the
// gradient near the load, then Newton converges within a few iterations), never decreasing; Interrupted when it
// returns false.
class GradientProgress {
public:
  explicit GradientProgress(const EquilibriumFitOptions& options) : options_(options) {}

  void report(int iteration, double gradient_norm, bool converged) {
    if (!options_.progress) return;
    const double target = options_.tolerance * options_.node_load;
    if (first_ < 0) first_ = gradient_norm;
    if (converged) {
      fraction_ = 1;
    } else {
      fraction_ = std::max(fraction_, static_cast<double>(iteration) / options_.max_iterations);
      if (first_ > target && gradient_norm > 0) {
        fraction_ = std::max(fraction_, std::clamp(std::log(first_ / gradient_norm) / std::log(first_ / target), 0.0, 1.0));
      }
    }
    if (!options_.progress(fraction_)) throw Interrupted();
  }

private:
  const EquilibriumFitOptions& options_;
  double first_ = -1;
  double fraction_ = 0;
};

}  // namespace

double equilibrium_potential(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                             const std::vector<Eigen::Vector3d>& anchor, const std::vector<Eigen::Vector3d>& positions,
                             const EquilibriumFitOptions& options) {
  const double k = max_stiffness(design);
  return potential(Model{surface, design, frame, anchor, options.node_load, options.contact_ratio * k,
                         options.anchor_ratio * k},
                   positions);
}

FittedPatch equilibrium_fit(const geometry::SurfaceMesh& surface, const PatchDesign& design, const PatchFrame& frame,
                            const EquilibriumFitOptions& options) {
  check_ranges(kEquilibriumFitParameters, options, "patch");
  FittedPatch fit = rigid_fit(surface, design, frame);
  if (fit.status == FitStatus::MissesSurface) return fit;
  const std::vector<Eigen::Vector3d> anchor = fit.positions;
  const double k = max_stiffness(design);
  const Model model{surface, design, frame, anchor, options.node_load, options.contact_ratio * k,
                    options.anchor_ratio * k};
  std::vector<Eigen::Vector3d> x = fit.positions;
  const int n = design.node_count();
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  double energy = potential(model, x);
  const double max_move = 0.25 * std::min(design.pitch_u, design.pitch_v);
  double radius = max_move;
  bool converged = false;
  int iteration = 0;
  GradientProgress progress(options);
  for (; iteration < options.max_iterations; ++iteration) {
    gradient_and_hessian(model, x, g, H);
    converged = g.lpNorm<Eigen::Infinity>() < options.tolerance * options.node_load;
    progress.report(iteration, g.lpNorm<Eigen::Infinity>(), converged);
    if (converged) break;
    // A small Levenberg shift keeps the system definite where a node is free in some direction.
    Eigen::SparseMatrix<double> I(3 * n, 3 * n);
    I.setIdentity();
    H += (1e-8 * k) * I;
    solver.compute(H);
    if (solver.info() != Eigen::Success) break;
    Eigen::VectorXd step = -solver.solve(g);
    // A flat membrane has no stiffness across its plane: limit every node's move to a quarter of the pitch (a
    // trust region), so the patch comes down onto the surface in steps instead of jumping through it.
    double largest = 0;
    for (int i = 0; i < n; ++i) largest = std::max(largest, step.segment<3>(3 * i).norm());
    if (largest > radius) step *= radius / largest;
    const double moved = std::min(largest, radius);
    double t = 1;
    bool accepted = false;
    for (int backtrack = 0; backtrack < 40; ++backtrack, t *= 0.5) {
      std::vector<Eigen::Vector3d> trial = x;
      for (int i = 0; i < n; ++i) trial[i] += t * step.segment<3>(3 * i);
      const double trial_energy = potential(model, trial);
      if (trial_energy <= energy + 1e-4 * t * g.dot(step)) {
        x = std::move(trial);
        energy = trial_energy;
        accepted = true;
        break;
      }
    }
    // Trust radius: shrink to the accepted move when the line search cut the step, grow when the full step passed.
    radius = t < 1 ? std::max(t * moved, 1e-6 * max_move) : std::min(2 * radius, max_move);
    if (!accepted) {
      // No decrease within round-off: converged as far as the energy can tell.
      converged = g.lpNorm<Eigen::Infinity>() < 1e3 * options.tolerance * options.node_load;
      break;
    }
  }
  fit.iterations = iteration;
  fit.positions = x;
  fit.normals = grid_normals(design, x, frame.approach);
  const double tolerance = 10 * options.node_load / model.contact;
  for (int i = 0; i < n; ++i) fit.on_surface[i] = std::abs(gap(surface, x[i]).first) <= tolerance;
  if (!converged && fit.status == FitStatus::Ok) {
    fit.status = FitStatus::NotConverged;
    fit.reason = fmt::format("Newton stopped after {} iterations with |grad|inf = {:.3g} N (tolerance {:.3g} N)",
                             iteration, g.lpNorm<Eigen::Infinity>(), options.tolerance * options.node_load);
  }
  return fit;
}

}  // namespace needlekit::patch
