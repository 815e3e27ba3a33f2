#include "needlekit/fem/quasi_static_solver.hpp"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "needlekit/core/errors.hpp"
#include "needlekit/fem/hyperelastic_law.hpp"
#include "needlekit/fem/tet_element.hpp"
#include "rigid_surface_distance.hpp"
#include "sparse_cholesky.hpp"
#include "sparse_pattern.hpp"
#include "tet_kernel.hpp"
#include "two_grid_preconditioner.hpp"

namespace needlekit::fem {

// ---- names ----------------------------------------------------------------------------------------------------
std::string to_string(MaterialLaw law) { return law == MaterialLaw::NeoHookean ? "neo-hookean" : "svk"; }
std::string to_string(ElementOrder order) { return order == ElementOrder::Quadratic ? "quadratic" : "linear"; }
std::string to_string(ContactModel contact) { return contact == ContactModel::Surface ? "surface" : "tip-nodes"; }
std::string to_string(LinearSolver solver) {
  switch (solver) {
    case LinearSolver::Cholesky: return "cholesky";
    case LinearSolver::CholeskyCg: return "cholesky-cg";
    case LinearSolver::TwoGrid: return "two-grid";
    default: return "auto";
  }
}
std::string to_string(BoundaryCondition c) {
  switch (c) {
    case BoundaryCondition::BottomFixed: return "bottom-fixed";
    case BoundaryCondition::BottomFixedSidesRoller: return "bottom-fixed-sides-roller";
    case BoundaryCondition::SymmetryPlanes: return "symmetry-planes";
    case BoundaryCondition::QuarterSymmetry: return "quarter-symmetry";
    default: return "sides-and-bottom-fixed";
  }
}
namespace {
[[noreturn]] void bad_choice(const std::string& what, const std::string& text, const std::string& expected) {
  throw InvalidInput(what + " = \"" + text + "\": expected " + expected);
}
}  // namespace
MaterialLaw material_law_from_string(const std::string& t, const std::string& what) {
  if (t == "svk" || t == "st-venant-kirchhoff") return MaterialLaw::StVenantKirchhoff;
  if (t == "neo-hookean") return MaterialLaw::NeoHookean;
  bad_choice(what, t, "\"svk\" or \"neo-hookean\"");
}
ElementOrder element_order_from_string(const std::string& t, const std::string& what) {
  if (t == "linear") return ElementOrder::Linear;
  if (t == "quadratic") return ElementOrder::Quadratic;
  bad_choice(what, t, "\"linear\" or \"quadratic\"");
}
ContactModel contact_model_from_string(const std::string& t, const std::string& what) {
  if (t == "tip-nodes") return ContactModel::TipNodes;
  if (t == "surface") return ContactModel::Surface;
  bad_choice(what, t, "\"tip-nodes\" or \"surface\"");
}
BoundaryCondition boundary_condition_from_string(const std::string& t, const std::string& what) {
  if (t == "sides-and-bottom-fixed") return BoundaryCondition::SidesAndBottomFixed;
  if (t == "bottom-fixed") return BoundaryCondition::BottomFixed;
  if (t == "bottom-fixed-sides-roller") return BoundaryCondition::BottomFixedSidesRoller;
  if (t == "symmetry-planes") return BoundaryCondition::SymmetryPlanes;
  if (t == "quarter-symmetry") return BoundaryCondition::QuarterSymmetry;
  bad_choice(what, t,
             "\"sides-and-bottom-fixed\", \"bottom-fixed\", \"bottom-fixed-sides-roller\", \"symmetry-planes\" or "
             "\"quarter-symmetry\"");
}

namespace {

using Clock = std::chrono::steady_clock;

// Inexact Newton: CG's relative tolerance for the first Newton iteration of a (sub)step and for the linearised
// predictor (a looser predictor costs Newton iterations: at 0.1, two-grid CG stopped after one iteration and the
// first step of a nearly incompressible T10 punch took 6 Newton solves instead of 5), and its upper bound.
constexpr double kFirstForcing = 1e-3;
constexpr double kMaxForcing = 1e-1;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string fmt_um(double m) {
  std::ostringstream s;
  s.precision(6);
  s << m * 1e6 << " um";
  return s.str();
}

struct NeedleState {
  Indenter indenter;
  Eigen::Vector3d direction;
  double gap = 0;                        // m, distance the needle travels before touching z_top
  std::vector<int> tip_nodes;            // TipNodes
  std::unique_ptr<detail::RigidSurfaceDistance> distance;  // Surface
  std::vector<double> lambda;            // Surface: augmented-Lagrangian force per top node, N
  std::vector<double> gap_now;           // Surface: signed gap per top node at the last evaluation, m
  std::vector<double> force_now;         // Surface: contact force per top node, N
  std::vector<Eigen::Vector3d> normal_now;
  std::vector<char> ahead;               // Surface: per top node, under the needle's leading faces at the last
                                         // converged state (see RigidSurfaceDistance::signed_distance)
};

}  // namespace

struct QuasiStaticSolver::Impl {
  SolverOptions opt;
  int nn = 0;                  // nodes per element (4 or 10)
  int nq = 0;                  // quadrature points per element
  std::vector<Eigen::Vector3d> nodes;
  std::vector<std::vector<int>> elements;
  std::vector<int> conn;       // flat, nn per element
  std::vector<double> grads;   // flat, nq * 3 * nn per element (column-major 3 x nn blocks)
  std::vector<double> weights; // nq per element
  std::vector<LameConstants> lame;
  std::vector<std::vector<int>> colors;
  double z_top = 0, h_min = 0, e_mean = 0, h_mean = 0;

  int ndof = 0;
  std::vector<int> free_index;   // per dof: index among free dofs or -1
  std::vector<int> free_dofs;
  std::vector<char> tip_dof;     // per dof: 1 when prescribed by a needle tip (TipNodes)
  detail::UpperPattern pattern;  // of the free-dof stiffness
  std::vector<int32_t> rows32;   // pattern.row_indices as 32-bit: the product's memory traffic is a quarter less
  std::vector<double> values;
  // Per element, (3N)^2 entries in column-major order of the element matrix: the index into `values` of the entry
  // (row dof, column dof) when both are free and row <= column, else -1. Built once: assembly then adds without
  // searching the pattern.
  std::vector<int32_t> value_slot;
  LinearSolver linear_solver = LinearSolver::CholeskyCg;  // resolved (never Automatic)
  std::unique_ptr<detail::SparseCholesky> cholesky;         // Cholesky, CholeskyCg
  std::unique_ptr<detail::TwoGridPreconditioner> two_grid;  // TwoGrid

  std::vector<int> top_nodes;              // nodes on the top surface (contact candidates)
  std::vector<double> node_area;           // per node: lumped top-surface area, m^2
  std::vector<double> node_stiffness;      // per node: penalty stiffness (force / length), N/m

  std::vector<NeedleState> needles;
  Eigen::VectorXd u, fint, fcontact;
  std::vector<Eigen::Vector3d> u_nodes;
  double d = 0;
  double external_work = 0;
  std::vector<double> last_force;
  std::vector<int> contact_flag;
  std::vector<double> contact_pressure;
  tbb::task_arena arena;

  // ---- evaluation -------------------------------------------------------------------------------------------
  struct Eval {
    double strain_energy = 0;
    double contact_energy = 0;
    bool valid = true;
    double potential() const { return strain_energy + contact_energy; }
  };

  template <int N>
  Eval element_pass(const Eigen::VectorXd& uu, bool want_force, bool want_tangent, const Eigen::VectorXd* dup,
                    Eigen::VectorXd* kdup) {
    tbb::combinable<double> energy([] { return 0.0; });
    std::atomic<bool> valid{true};
    if (want_force) fint.setZero(ndof);
    if (want_tangent) std::fill(values.begin(), values.end(), 0.0);
    for (const auto& color : colors) {
      arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, color.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
          Eigen::Matrix<double, 3, N> ue, fe;
          Eigen::Matrix<double, 3 * N, 3 * N> ke;
          double& en = energy.local();
          for (size_t k = r.begin(); k < r.end(); ++k) {
            const int e = color[k];
            const int* c = &conn[static_cast<size_t>(e) * N];
            for (int a = 0; a < N; ++a) ue.col(a) = uu.segment<3>(3 * c[a]);
            const auto* g = reinterpret_cast<const detail::Grad<N>*>(&grads[static_cast<size_t>(e) * nq * 3 * N]);
            double we;
            if (!want_force) {
              // energy only
              for (int q = 0; q < nq; ++q) {
                const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + ue * g[q].transpose();
                const auto s = stress_response(opt.law, lame[e], f, false);
                if (!s.valid) valid = false;
                else en += weights[static_cast<size_t>(e) * nq + q] * s.energy_density;
              }
              continue;
            }
            const bool ok = detail::tet_kernel<N>(g, &weights[static_cast<size_t>(e) * nq], nq, opt.law, lame[e], ue,
                                                  we, fe, want_tangent ? &ke : nullptr);
            if (!ok) {
              valid = false;
              continue;
            }
            en += we;
            for (int a = 0; a < N; ++a) fint.segment<3>(3 * c[a]) += fe.col(a);
            if (!want_tangent) continue;
            const int32_t* slot = &value_slot[static_cast<size_t>(e) * 9 * N * N];
            for (int col = 0; col < 3 * N; ++col)
              for (int row = 0; row < 3 * N; ++row)
                if (slot[col * 3 * N + row] >= 0) values[static_cast<size_t>(slot[col * 3 * N + row])] += ke(row, col);
            if (!kdup) continue;
            // Coupling to the prescribed tip dofs: the linear predictor's right-hand side K_fp du_p.
            for (int a = 0; a < N; ++a)
              for (int i = 0; i < 3; ++i) {
                const int ra = free_index[3 * c[a] + i];
                if (ra < 0) continue;
                for (int b = 0; b < N; ++b)
                  for (int j = 0; j < 3; ++j) {
                    const int dofb = 3 * c[b] + j;
                    if (free_index[dofb] < 0) (*kdup)[ra] += ke(3 * a + i, 3 * b + j) * (*dup)[dofb];
                  }
              }
          }
        });
      });
    }
    Eval ev;
    ev.strain_energy = energy.combine([](double x, double y) { return x + y; });
    ev.valid = valid;
    return ev;
  }

  // Contact terms (Surface): energy, forces into fcontact, penalty tangent k n n^T into values.
  double contact_pass(const Eigen::VectorXd& uu, double disp, bool want_force, bool want_tangent) {
    if (opt.contact != ContactModel::Surface) return 0;
    if (want_force) fcontact.setZero(ndof);
    double energy = 0;
    for (auto& nd : needles) {
      const Eigen::Vector3d shift = disp * nd.direction;
      double margin = 0;
      for (size_t t = 0; t < top_nodes.size(); ++t)
        margin = std::max(margin, nd.lambda[t] / node_stiffness[top_nodes[t]]);
      margin += 1e-9 * (nd.distance->box_max() - nd.distance->box_min()).norm();
      const Eigen::Vector3d lo = nd.distance->box_min().array() - margin, hi = nd.distance->box_max().array() + margin;
      for (size_t t = 0; t < top_nodes.size(); ++t) {
        const int a = top_nodes[t];
        const double k = node_stiffness[a];
        const Eigen::Vector3d q = nodes[a] + uu.segment<3>(3 * a) - shift;
        nd.force_now[t] = 0;
        nd.gap_now[t] = std::numeric_limits<double>::infinity();
        if ((q.array() < lo.array()).any() || (q.array() > hi.array()).any()) continue;
        const auto sd =
            nd.distance->signed_distance(q, (nd.distance->box_max() - nd.distance->box_min()).norm(), nd.ahead[t]);
        nd.gap_now[t] = sd.distance;
        const double p = nd.lambda[t] - k * sd.distance;
        if (p <= 0) continue;
        energy += p * p / (2 * k);
        nd.force_now[t] = p;
        nd.normal_now[t] = sd.normal;
        if (want_force) fcontact.segment<3>(3 * a) += p * sd.normal;
        if (!want_tangent) continue;
        const Eigen::Matrix3d kn = k * sd.normal * sd.normal.transpose();
        for (int i = 0; i < 3; ++i) {
          const int r = free_index[3 * a + i];
          if (r < 0) continue;
          for (int j = 0; j < 3; ++j) {
            const int c = free_index[3 * a + j];
            if (c < 0 || r > c) continue;
            values[static_cast<size_t>(detail::entry_position(pattern, r, c))] += kn(i, j);
          }
        }
      }
    }
    return energy;
  }

  Eval evaluate(const Eigen::VectorXd& uu, double disp, bool want_force, bool want_tangent,
                const Eigen::VectorXd* dup = nullptr, Eigen::VectorXd* kdup = nullptr) {
    Eval ev = nn == 4 ? element_pass<4>(uu, want_force, want_tangent, dup, kdup)
                      : element_pass<10>(uu, want_force, want_tangent, dup, kdup);
    if (ev.valid) ev.contact_energy = contact_pass(uu, disp, want_force, want_tangent);
    return ev;
  }

  Eigen::VectorXd free_residual() const {
    Eigen::VectorXd r(static_cast<Eigen::Index>(free_dofs.size()));
    const bool surf = opt.contact == ContactModel::Surface;
    for (size_t k = 0; k < free_dofs.size(); ++k)
      r[static_cast<Eigen::Index>(k)] = fint[free_dofs[k]] - (surf ? fcontact[free_dofs[k]] : 0.0);
    return r;
  }

  double tip_value(const NeedleState& nd, double disp) const { return -std::max(0.0, disp - nd.gap); }

  // y = K x for the upper-triangular CSC values. Threaded over column ranges; each range scatters its transposed
  // part into its own vector (the symmetric product writes rows above the range), summed at the end.
  std::vector<Eigen::VectorXd> partial;  // multiply's per-range products, kept between calls (CG's hot path)

  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    const int64_t nc = static_cast<int64_t>(pattern.column_pointers.size()) - 1;
    const int parts = std::max(1, arena.max_concurrency());
    partial.resize(static_cast<size_t>(parts));
    arena.execute([&] {
      tbb::parallel_for(0, parts, [&](int part) {
        Eigen::VectorXd& yp = partial[static_cast<size_t>(part)];
        yp.setZero(x.size());
        // Equal shares of the stored entries, not of the columns (columns grow longer towards the end).
        const auto begin_column = [&](int q) {
          const int64_t target = pattern.column_pointers.back() * q / parts;
          return static_cast<int64_t>(std::lower_bound(pattern.column_pointers.begin(), pattern.column_pointers.end(), target) - pattern.column_pointers.begin());
        };
        const int64_t c0 = std::min(begin_column(part), nc), c1 = part + 1 == parts ? nc : std::min(begin_column(part + 1), nc);
        for (int64_t c = c0; c < c1; ++c) {
          const double xc = x[c];
          const int64_t diagonal = pattern.column_pointers[c + 1] - 1;  // every column ends with its diagonal
          double acc = values[static_cast<size_t>(diagonal)] * xc;
          for (int64_t k = pattern.column_pointers[c]; k < diagonal; ++k) {
            const int32_t r = rows32[static_cast<size_t>(k)];
            const double v = values[static_cast<size_t>(k)];
            acc += v * x[r];
            yp[r] += v * xc;
          }
          yp[c] += acc;
        }
      });
    });
    y = partial[0];
    for (size_t p = 1; p < partial.size(); ++p) y += partial[p];
  }

  bool have_factor = false;
  Eigen::VectorXd last_increment;  // u change of the last converged substep (for the secant predictor)
  double last_step = 0;            // m, its needle displacement change
  // Cost balance of the reused factorization: CG on the last factor is worth it while its iterations cost less than
  // a fresh factorization. The costs are estimated from the pattern, not timed, so that a run does not depend on the
  // machine's load: a factorization takes CHOLMOD's flop count, a CG iteration 4 (nnz(L) + nnz(K)) flops (two
  // triangular solves and the symmetric product), and a factorization's flops run kFactorFlopSpeedup times faster
  // (dense BLAS-3 kernels against memory-bound triangular solves; measured 6.6 and 7.5 on the 100k- and 300k-tet
  // skin blocks of BENCHMARKS.md).
  static constexpr double kFactorFlopSpeedup = 7.0;
  int last_cg_iterations = 0;  // of the last CG solve

  // CG iterations worth trying before a factorization is cheaper, within [1, max_reuse_iterations].
  int cg_budget() const {
    const double cg_flops = 4.0 * (cholesky->factor_nonzeros() + static_cast<double>(values.size()));
    return static_cast<int>(std::clamp(cholesky->factor_flops() / (kFactorFlopSpeedup * cg_flops), 1.0,
                                       static_cast<double>(opt.max_reuse_iterations)));
  }

  Eigen::VectorXd apply_factor(const Eigen::VectorXd& r) {
    const std::vector<double> b(r.data(), r.data() + r.size());
    const auto x = cholesky->solve(b);
    return Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
  }

  // Krylov recycling: the last solutions span most of the next one (successive Newton corrections and load steps
  // deform the tissue alike). CG starts from the Galerkin projection of the solution onto them,
  // x0 = W (W^T K W)^-1 W^T b, and only has to resolve what they miss.
  static constexpr int kRecycled = 12;
  std::vector<Eigen::VectorXd> recycled;  // unit vectors, newest last
  std::vector<Eigen::VectorXd> recycled_products;  // K times each, recomputed per solve (K changes); storage kept

  void remember(const Eigen::VectorXd& solution) {
    const double n = solution.norm();
    if (!(n > 0) || !solution.allFinite()) return;
    if (static_cast<int>(recycled.size()) == kRecycled) recycled.erase(recycled.begin());
    recycled.push_back(solution / n);
  }

  void recycled_start(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, Eigen::VectorXd& r) {
    const int m = static_cast<int>(recycled.size());
    if (m == 0) return;
    std::vector<Eigen::VectorXd>& kw = recycled_products;
    kw.resize(static_cast<size_t>(m));
    Eigen::MatrixXd g(m, m);
    Eigen::VectorXd wb(m);
    for (int i = 0; i < m; ++i) multiply(recycled[static_cast<size_t>(i)], kw[static_cast<size_t>(i)]);
    for (int i = 0; i < m; ++i) {
      wb[i] = recycled[static_cast<size_t>(i)].dot(rhs);
      for (int j = 0; j < m; ++j) g(i, j) = recycled[static_cast<size_t>(i)].dot(kw[static_cast<size_t>(j)]);
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(g);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return;
    const Eigen::VectorXd y = ldlt.solve(wb);
    if (!y.allFinite()) return;
    for (int i = 0; i < m; ++i) {
      x += y[i] * recycled[static_cast<size_t>(i)];
      r -= y[i] * kw[static_cast<size_t>(i)];
    }
  }

  // Preconditioned CG on the current values; false if it does not converge in `budget` iterations.
  template <class Preconditioner>
  bool cg_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int& iterations, double tolerance, int budget,
                Preconditioner&& precondition) {
    const double bnorm = rhs.norm();
    x = Eigen::VectorXd::Zero(rhs.size());
    if (bnorm == 0) return true;
    Eigen::VectorXd r = rhs;
    recycled_start(rhs, x, r);
    if (r.norm() <= tolerance * bnorm) {
      iterations = 0;
      return x.allFinite();
    }
    Eigen::VectorXd z, p, q;
    precondition(r, z);
    p = z;
    double rz = r.dot(z);
    for (iterations = 1; iterations <= budget; ++iterations) {
      multiply(p, q);
      const double pq = p.dot(q);
      if (!(pq > 0)) return false;  // not positive definite along p
      const double alpha = rz / pq;
      x += alpha * p;
      r -= alpha * q;
      if (r.norm() <= tolerance * bnorm) return x.allFinite();
      precondition(r, z);
      const double rz_new = r.dot(z);
      p = z + (rz_new / rz) * p;
      rz = rz_new;
    }
    return false;
  }

  // `shifted` = `base` with its diagonal raised by the fraction beta (for a tangent that is not positive definite);
  // the off-diagonal entries of `shifted` are left as they are. The diagonal is the last entry of each column.
  void shift_diagonal(const std::vector<double>& base, double beta, std::vector<double>& shifted) const {
    for (size_t c = 0; c + 1 < pattern.column_pointers.size(); ++c) {
      const auto diagonal = static_cast<size_t>(pattern.column_pointers[c + 1] - 1);
      shifted[diagonal] = base[diagonal] * (1 + beta);
    }
  }

  // Solve K du = rhs: CG preconditioned by the last factorization when allowed, else (or on failure) a fresh
  // factorization (with a diagonal shift if K is not positive definite).
  // `forcing`: the relative residual at which CG may stop (inexact Newton); never below linear_tolerance.
  bool factor_and_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing) {
    if (linear_solver == LinearSolver::TwoGrid) return two_grid_solve(rhs, du, rec, forcing);
    // CG on the old factor, unless the last CG solve cost more than half a factorization: then refactorize now
    // rather than after a failed CG.
    const int budget = cg_budget();
    if (linear_solver == LinearSolver::CholeskyCg && have_factor && 2 * last_cg_iterations <= budget) {
      int its = 0;
      const double tol = std::max(forcing, opt.linear_tolerance);
      const auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = apply_factor(r); };
      if (cg_solve(rhs, du, its, tol, budget, precondition)) {
        last_cg_iterations = its;
        rec.linear_iterations = its;
        remember(du);
        return true;
      }
    }
    last_cg_iterations = 0;
    rec.factorized = true;
    rec.linear_iterations = 0;
    have_factor = false;
    if (!cholesky->factorize(values)) {
      bool ok = false;
      std::vector<double> shifted = values;
      for (double beta : {1e-6, 1e-4, 1e-2, 1e-1, 1.0}) {
        shift_diagonal(values, beta, shifted);
        if (cholesky->factorize(shifted)) {
          ok = true;
          break;
        }
      }
      if (!ok) return false;
    }
    have_factor = true;
    du = apply_factor(rhs);
    remember(du);
    return du.allFinite();
  }

  // CG with the two-grid cycle. The coarse operator (and the smoother's spectral bound) is renewed when missing,
  // when the last solve needed more than two_grid_refresh_iterations, or when CG fails on the stale one. If CG still
  // fails (K not positive definite: SVK under strong compression), the tangent's diagonal is raised by growing
  // fractions, as for a failed factorization: a shifted Newton step is still a descent direction.
  static constexpr int kTwoGridMaxIterations = 200;
  bool two_grid_solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing) {
    const auto multiply_k = [this](const Eigen::VectorXd& x, Eigen::VectorXd& y) { multiply(x, y); };
    const auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { two_grid->apply(r, z, multiply_k); };
    const double tol = std::max(forcing, opt.linear_tolerance);
    int its = 0;
    rec.linear_iterations = 0;
    const bool stale = have_factor && last_cg_iterations <= opt.two_grid_refresh_iterations;
    if (stale) {
      two_grid->set_smoother_diagonal(values);  // K changed since the last solve; update() sets it itself
      if (cg_solve(rhs, du, its, tol, kTwoGridMaxIterations, precondition)) {
        rec.linear_iterations = last_cg_iterations = its;
        remember(du);
        return true;
      }
      rec.linear_iterations = its;
    }
    rec.factorized = true;
    bool ok = (have_factor = two_grid->update(values, multiply_k)) &&
              cg_solve(rhs, du, its, tol, kTwoGridMaxIterations, precondition);
    rec.linear_iterations += its;
    if (!ok) {
      const std::vector<double> unshifted = values;
      for (double beta : {1e-4, 1e-2, 1e-1, 1.0}) {
        shift_diagonal(unshifted, beta, values);
        ok = (have_factor = two_grid->update(values, multiply_k)) &&
             cg_solve(rhs, du, its, tol, kTwoGridMaxIterations, precondition);
        rec.linear_iterations += its;
        if (ok) break;
      }
      values = unshifted;
      have_factor = false;  // the coarse operator was the shifted one's
    }
    last_cg_iterations = its;
    if (ok) remember(du);
    return ok;
  }

  // One iteration's linear solve (predictor or Newton), timed and counted into `rec` and `res`.
  bool solve_iteration(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& rec, double forcing,
                       StepResult& res, std::string& why) {
    const auto t0 = Clock::now();
    if (!factor_and_solve(rhs, du, rec, forcing)) {
      why = linear_solver == LinearSolver::TwoGrid
                ? "the tangent system could not be solved (two-grid CG failed, also with a diagonal shift)"
                : "the tangent matrix could not be factorized";
      return false;
    }
    rec.solve_seconds = seconds_since(t0);
    rec.increment_norm = du.norm();
    if (rec.factorized) res.factorizations++;
    return true;
  }

  // Adds a finished iteration to the step's record.
  static void book(const IterationRecord& rec, StepResult& res) {
    res.iterations.push_back(rec);
    res.newton_iterations++;
    res.assembly_seconds += rec.assembly_seconds;
    res.solve_seconds += rec.solve_seconds;
  }

  void add_free(Eigen::VectorXd& uu, const Eigen::VectorXd& du, double alpha) const {
    for (size_t k = 0; k < free_dofs.size(); ++k) uu[free_dofs[k]] += alpha * du[static_cast<Eigen::Index>(k)];
  }

  // Newton with backtracking line search at fixed needle displacement `disp` (and fixed multipliers).
  bool newton(double disp, StepResult& res, std::string& why, int cutbacks_so_far) {
    const double tiny = 1e-14 * e_mean * h_mean * h_mean;
    double first_energy_norm = 0, last_du = std::numeric_limits<double>::infinity(), last_en = last_du;
    // Forces and tangent at u: assembled here for the first iteration, afterwards by the line search's full-step
    // trial when that step is accepted (the usual case), so an accepted full step costs one assembly, not two.
    bool assembled = false;
    double carried_assembly_seconds = 0, previous_residual = 0;
    Eval ev;
    for (int it = 1; it <= opt.max_iterations + 1; ++it) {
      IterationRecord rec;
      auto t0 = Clock::now();
      if (!assembled) ev = evaluate(u, disp, true, true);
      rec.assembly_seconds = assembled ? carried_assembly_seconds : seconds_since(t0);
      assembled = false;
      if (!ev.valid) {
        why = "an element inverted (J <= 0)";
        return false;
      }
      const Eigen::VectorXd r = free_residual();
      rec.residual_norm = r.norm();
      if (!std::isfinite(rec.residual_norm)) {
        why = "the residual is not finite";
        return false;
      }
      const double ref = std::max({fint.norm(), opt.contact == ContactModel::Surface ? fcontact.norm() : 0.0, tiny});
      double unorm = 0;
      for (int dof : free_dofs) unorm += u[dof] * u[dof];
      unorm = std::sqrt(unorm);
      const bool res_ok = rec.residual_norm <= opt.residual_tolerance * ref;
      const bool disp_ok = last_du <= opt.displacement_tolerance * std::max(unorm, 1e-300);
      const bool energy_ok = it > 1 && last_en <= opt.energy_tolerance * first_energy_norm;
      if (rec.residual_norm <= tiny * 1e-6 || (res_ok && (disp_ok || energy_ok))) return true;
      if (it > opt.max_iterations) {
        why = "Newton did not converge in " + std::to_string(opt.max_iterations) + " iterations (residual " +
              std::to_string(rec.residual_norm / ref) + " of the force scale)";
        return false;
      }
      Eigen::VectorXd du;
      // Forcing term (Eisenstat & Walker 1996, choice 2): eta = (|r_k| / |r_k-1|)^2, at most kMaxForcing, and no
      // tighter than leaving a tenth of the convergence target. Loose while far from the solution, tight near it,
      // without spoiling Newton's quadratic convergence.
      // (std::min/max, not std::clamp: the lower bound exceeds kMaxForcing once the residual is below its target
      // and Newton still iterates for the displacement or energy test.)
      const double suggested =
          previous_residual > 0 ? std::pow(rec.residual_norm / previous_residual, 2) : kFirstForcing;
      const double eta =
          std::min(kMaxForcing, std::max(suggested, 0.1 * opt.residual_tolerance * ref / rec.residual_norm));
      previous_residual = rec.residual_norm;
      if (!solve_iteration(-r, du, rec, eta, res, why)) return false;
      const double slope = r.dot(du);
      rec.energy_norm = std::abs(slope);
      if (it == 1) first_energy_norm = rec.energy_norm;
      double alpha = 1;
      if (opt.line_search && slope < 0) {
        const double pi0 = ev.potential();
        const auto sufficient = [&](const Eval& e, double a) {
          return e.valid && e.potential() <= pi0 + 1e-4 * a * slope + 1e-10 * std::abs(pi0);
        };
        Eigen::VectorXd trial = u;
        add_free(trial, du, 1.0);
        t0 = Clock::now();
        const Eval full = evaluate(trial, disp, true, true);  // the next iteration's assembly if accepted
        carried_assembly_seconds = seconds_since(t0);
        assembled = sufficient(full, 1.0);
        if (assembled) ev = full;
        for (int ls = 1; !assembled; ++ls) {
          alpha *= 0.5;
          trial = u;
          add_free(trial, du, alpha);
          const Eval et = evaluate(trial, disp, false, false);
          if (sufficient(et, alpha)) break;
          if (ls >= 12) {
            // No sufficient decrease (a kink of the contact energy or round-off): take the full Newton step and let
            // the convergence test and the iteration limit decide.
            alpha = 1;
            rec.line_search_failed = true;
            break;
          }
        }
      }
      rec.step_length = alpha;
      add_free(u, du, alpha);
      last_du = alpha * rec.increment_norm;
      last_en = alpha * rec.energy_norm;
      book(rec, res);
      if (opt.progress) opt.progress({disp, it, rec.residual_norm, cutbacks_so_far});
    }
    return false;
  }

  double max_penetration() const {
    double pen = 0;
    for (const auto& nd : needles)
      for (size_t t = 0; t < top_nodes.size(); ++t)
        if (std::isfinite(nd.gap_now[t])) pen = std::max(pen, -nd.gap_now[t]);
    return pen;
  }

  // Surface: which top nodes are ahead of each needle in the converged state (u, disp): their nearest point on the
  // needle's surface has an outward normal along the direction of motion (under a leading face or its rim), or they
  // are out of reach. Nodes beside the needle (nearest a side wall) are not.
  void update_ahead(double disp) {
    for (auto& nd : needles) {
      const double reach = (nd.distance->box_max() - nd.distance->box_min()).norm();
      for (size_t t = 0; t < top_nodes.size(); ++t) {
        const int a = top_nodes[t];
        const auto sd = nd.distance->signed_distance(nodes[a] + u.segment<3>(3 * a) - disp * nd.direction, reach);
        nd.ahead[t] = sd.distance >= reach || sd.normal.dot(nd.direction) > detail::RigidSurfaceDistance::kLeadingCosine;
      }
    }
  }

  // One substep from the current converged state (u, d) to displacement `target`.
  bool substep(double target, StepResult& res, std::string& why, int cutbacks_so_far) {
    // Secant predictor: the last converged state plus the last step's increment scaled to this step.
    const bool extrapolate = opt.extrapolate_predictor && last_step != 0 && last_increment.size() == ndof;
    if (extrapolate) u += ((target - d) / last_step) * last_increment;
    if (opt.contact == ContactModel::TipNodes) {
      Eigen::VectorXd dup = Eigen::VectorXd::Zero(ndof);
      for (const auto& nd : needles)
        for (int a : nd.tip_nodes) {
          const int dof = 3 * a + 2;
          if (tip_dof[dof]) dup[dof] = tip_value(nd, target) - u[dof];
        }
      if (!extrapolate && opt.linear_predictor && dup.squaredNorm() > 0) {
        // §3.4: first iterate = linear(ised) elastic solution: K_ff du_f = -(R_f + K_fp du_p).
        IterationRecord rec;
        auto t0 = Clock::now();
        Eigen::VectorXd kdup = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(free_dofs.size()));
        const Eval ev = evaluate(u, target, true, true, &dup, &kdup);
        rec.assembly_seconds = seconds_since(t0);
        if (!ev.valid) {
          why = "an element inverted (J <= 0)";
          return false;
        }
        const Eigen::VectorXd r = free_residual();
        rec.residual_norm = r.norm();
        Eigen::VectorXd du;
        if (!solve_iteration(-(r + kdup), du, rec, kFirstForcing, res, why)) return false;
        add_free(u, du, 1.0);
        book(rec, res);
      }
      u += dup;
      return newton(target, res, why, cutbacks_so_far);
    }
    // Surface contact: Newton at fixed multipliers, then augmented-Lagrangian updates.
    for (int aug = 0;; ++aug) {
      if (!newton(target, res, why, cutbacks_so_far)) return false;
      const double pen = max_penetration();
      if (pen <= opt.penetration_tolerance * std::max(std::abs(target), h_min) || aug >= opt.max_augmentations) {
        update_ahead(target);
        return true;
      }
      for (auto& nd : needles)
        for (size_t t = 0; t < top_nodes.size(); ++t) nd.lambda[t] = nd.force_now[t];
    }
  }

  // Forces, pressures and flags of the converged state (fint/fcontact of the last evaluation).
  void measure(StepResult& res) {
    const size_t m = needles.size();
    res.indenter_force.assign(m, 0);
    res.max_contact_pressure.assign(m, 0);
    res.mean_contact_pressure.assign(m, 0);
    res.contact_area.assign(m, 0);
    res.contact_nodes.assign(m, 0);
    std::fill(contact_flag.begin(), contact_flag.end(), 0);
    std::fill(contact_pressure.begin(), contact_pressure.end(), 0.0);
    for (size_t k = 0; k < m; ++k) {
      auto& nd = needles[k];
      bool any = false;
      auto record = [&](int a, double force) {
        const double p = node_area[a] > 0 ? force / node_area[a] : 0;
        contact_flag[a] = static_cast<int>(k) + 1;
        contact_pressure[a] = p;
        res.indenter_force[k] += force;
        res.contact_area[k] += node_area[a];
        res.contact_nodes[k]++;
        res.max_contact_pressure[k] = any ? std::max(res.max_contact_pressure[k], p) : p;
        any = true;
      };
      if (opt.contact == ContactModel::TipNodes) {
        if (d > nd.gap)
          for (int a : nd.tip_nodes)
            if (tip_dof[3 * a + 2]) record(a, fint.segment<3>(3 * a).dot(nd.direction));  // Eq 3.11
      } else {
        for (size_t t = 0; t < top_nodes.size(); ++t)
          if (nd.force_now[t] > 0) record(top_nodes[t], nd.force_now[t] * nd.normal_now[t].dot(nd.direction));
      }
      if (res.contact_area[k] > 0) res.mean_contact_pressure[k] = res.indenter_force[k] / res.contact_area[k];
    }
    res.max_penetration = opt.contact == ContactModel::Surface ? max_penetration() : 0.0;
  }
};

// ---- construction ---------------------------------------------------------------------------------------------
namespace {
void check(bool ok, const std::string& message) {
  if (!ok) throw InvalidInput(message);
}
template <class T>
std::string str(T v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

QuasiStaticSolver::QuasiStaticSolver(const mesh::TetMesh& mesh, std::vector<Indenter> indenters, SolverOptions options,
                                     const mesh::CoarseLevel* coarse)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  m.opt = std::move(options);
  const auto& o = m.opt;
  check(o.residual_tolerance > 0 && o.residual_tolerance < 1, "solver residual_tolerance = " +
        str(o.residual_tolerance) + ": expected (0, 1)");
  check(o.displacement_tolerance > 0 && o.displacement_tolerance < 1,
        "solver displacement_tolerance = " + str(o.displacement_tolerance) + ": expected (0, 1)");
  check(o.energy_tolerance > 0 && o.energy_tolerance < 1,
        "solver energy_tolerance = " + str(o.energy_tolerance) + ": expected (0, 1)");
  check(o.max_iterations >= 1, "solver max_iterations = " + str(o.max_iterations) + ": expected >= 1");
  check(o.max_cutbacks >= 0, "solver max_cutbacks = " + str(o.max_cutbacks) + ": expected >= 0");
  check(o.penalty_factor > 0, "solver penalty_factor = " + str(o.penalty_factor) + ": expected > 0");
  check(o.penetration_tolerance > 0 && o.penetration_tolerance < 1,
        "solver penetration_tolerance = " + str(o.penetration_tolerance) + ": expected (0, 1)");
  check(o.max_augmentations >= 0, "solver max_augmentations = " + str(o.max_augmentations) + ": expected >= 0");
  check(o.boundary_tolerance >= 0, "solver boundary_tolerance = " + str(o.boundary_tolerance) + ": expected >= 0");
  check(o.max_reuse_iterations >= 1,
        "solver max_reuse_iterations = " + str(o.max_reuse_iterations) + ": expected >= 1");
  check(o.linear_tolerance > 0 && o.linear_tolerance < 1,
        "solver linear_tolerance = " + str(o.linear_tolerance) + ": expected (0, 1)");
  check(o.threads >= 0, "solver threads = " + str(o.threads) + ": expected >= 0");
  check(o.two_grid_refresh_iterations >= 1,
        "solver two_grid_refresh_iterations = " + str(o.two_grid_refresh_iterations) + ": expected >= 1");
  check(o.linear_solver != LinearSolver::TwoGrid || coarse || o.order == ElementOrder::Quadratic,
        "solver linear_solver = \"two-grid\" needs a coarse level for linear elements: a mesh split from a coarser "
        "one (mesh::refine_uniformly; [mesh] split = true in a case file)");
  if (coarse && o.order == ElementOrder::Linear) {
    check(coarse->node_parents.size() == mesh.nodes.size(),
          "coarse level: " + str(coarse->node_parents.size()) + " node parents for " + str(mesh.nodes.size()) +
              " nodes");
    for (const auto& parents : coarse->node_parents)
      for (int a : parents)
        if (a < 0 || a >= coarse->nodes)
          throw InvalidInput("coarse level: parent node " + str(a) + " outside [0, " + str(coarse->nodes) + ")");
  }
  m.arena.initialize(o.threads > 0 ? o.threads : tbb::task_arena::automatic);

  // Mesh validation.
  check(!mesh.nodes.empty() && !mesh.tets.empty(), "tissue mesh: no nodes or no tetrahedra");
  check(mesh.tet_layer.size() == mesh.tets.size(), "tissue mesh: tet_layer has " + str(mesh.tet_layer.size()) +
        " entries for " + str(mesh.tets.size()) + " tetrahedra");
  for (size_t l = 0; l < mesh.layers.size(); ++l) {
    const auto& L = mesh.layers[l];
    check(L.youngs_modulus > 0 && std::isfinite(L.youngs_modulus),
          "tissue layer \"" + L.name + "\": youngs_modulus = " + str(L.youngs_modulus) + " Pa, expected > 0");
    check(L.poisson_ratio > -1 && L.poisson_ratio < 0.5,
          "tissue layer \"" + L.name + "\": poisson_ratio = " + str(L.poisson_ratio) + ", expected (-1, 0.5)");
  }
  const int n0 = static_cast<int>(mesh.nodes.size());
  Eigen::Vector3d lo = mesh.nodes[0], hi = mesh.nodes[0];
  for (const auto& p : mesh.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diag = (hi - lo).norm();
  for (size_t e = 0; e < mesh.tets.size(); ++e) {
    const auto& t = mesh.tets[e];
    // (Messages are built only on failure: building them for every element took 2 s at 300k tetrahedra.)
    for (int a : t)
      if (a < 0 || a >= n0)
        throw InvalidInput("tissue mesh: tetrahedron " + str(e) + " has node index " + str(a) + " outside [0, " +
                           str(n0) + ")");
    if (mesh.tet_layer[e] < 0 || mesh.tet_layer[e] >= static_cast<int>(mesh.layers.size()))
      throw InvalidInput("tissue mesh: tetrahedron " + str(e) + " has layer " + str(mesh.tet_layer[e]) +
                         " but the mesh has " + str(mesh.layers.size()) + " layers");
    const auto& p = mesh.nodes;
    const double v = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) / 6;
    double lmax = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) lmax = std::max(lmax, (p[t[i]] - p[t[j]]).norm());
    if (!(v > 1e-10 * lmax * lmax * lmax))
      throw InvalidInput("tissue mesh: tetrahedron " + str(e) + " is " + (v < 0 ? "inverted" : "degenerate") +
                         " (volume " + str(v) + " m^3, longest edge " + str(lmax) + " m)");
  }

  // Nodes and elements (T10: one mid-edge node per edge).
  m.nn = o.order == ElementOrder::Quadratic ? 10 : 4;
  m.nq = m.nn == 4 ? 1 : 4;
  m.nodes = mesh.nodes;
  const size_t ne = mesh.tets.size();
  m.conn.resize(ne * m.nn);
  for (size_t e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a) m.conn[e * m.nn + a] = mesh.tets[e][a];
  std::vector<std::pair<int64_t, int>> edge_keys;  // (key, tet*6+k)
  mesh::CoarseLevel corners;  // T10: the corner nodes as the two-grid solver's coarse level
  if (m.nn == 10) {
    corners.nodes = n0;
    corners.tets = mesh.tets;
    corners.node_parents.resize(static_cast<size_t>(n0));
    for (int a = 0; a < n0; ++a) corners.node_parents[static_cast<size_t>(a)] = {a, a};
    edge_keys.reserve(ne * 6);
    for (size_t e = 0; e < ne; ++e)
      for (int k = 0; k < 6; ++k) {
        int a = mesh.tets[e][detail::tet_edges[k][0]], b = mesh.tets[e][detail::tet_edges[k][1]];
        if (a > b) std::swap(a, b);
        edge_keys.emplace_back(static_cast<int64_t>(a) * n0 + b, static_cast<int>(e * 6 + k));
      }
    std::sort(edge_keys.begin(), edge_keys.end());
    int64_t prev = -1;
    int id = n0 - 1;
    for (const auto& [key, slot] : edge_keys) {
      if (key != prev) {
        ++id;
        prev = key;
        const int a = static_cast<int>(key / n0), b = static_cast<int>(key % n0);
        m.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
        corners.node_parents.push_back({a, b});
      }
      m.conn[static_cast<size_t>(slot / 6) * 10 + 4 + slot % 6] = id;
    }
  }
  const int nnode = static_cast<int>(m.nodes.size());
  m.ndof = 3 * nnode;
  m.elements.resize(ne);
  m.lame.resize(ne);
  m.grads.resize(ne * m.nq * 3 * m.nn);
  m.weights.resize(ne * m.nq);
  double vol_sum = 0, e_sum = 0;
  std::vector<double> node_e(nnode, 0.0), node_vol(nnode, 0.0);
  std::vector<int> node_cnt(nnode, 0);
  for (size_t e = 0; e < ne; ++e) {
    std::vector<Eigen::Vector3d> x(m.nn);
    m.elements[e].assign(m.conn.begin() + e * m.nn, m.conn.begin() + (e + 1) * m.nn);
    for (int a = 0; a < m.nn; ++a) x[a] = m.nodes[m.conn[e * m.nn + a]];
    const auto geo = element_geometry(x);
    for (int q = 0; q < m.nq; ++q) {
      m.weights[e * m.nq + q] = geo.weights[q];
      std::copy(geo.gradients[q].data(), geo.gradients[q].data() + 3 * m.nn, &m.grads[(e * m.nq + q) * 3 * m.nn]);
    }
    const auto& layer = mesh.layers[mesh.tet_layer[e]];
    m.lame[e] = lame_constants(layer.youngs_modulus, layer.poisson_ratio);
    vol_sum += geo.volume;
    e_sum += layer.youngs_modulus * geo.volume;
    for (int a = 0; a < m.nn; ++a) {
      const int n = m.conn[e * m.nn + a];
      node_e[n] = std::max(node_e[n], layer.youngs_modulus);
      node_vol[n] += geo.volume;
      node_cnt[n]++;
    }
  }
  m.e_mean = e_sum / vol_sum;
  m.h_mean = std::cbrt(6 * std::sqrt(2.0) * vol_sum / ne);

  // Element colouring: no two elements of a colour share a node (lock-free threaded assembly).
  {
    std::vector<std::array<uint64_t, 4>> used(nnode, {0, 0, 0, 0});
    std::vector<int> color(ne);
    int ncolor = 0;
    for (size_t e = 0; e < ne; ++e) {
      std::array<uint64_t, 4> mask{0, 0, 0, 0};
      for (int a = 0; a < m.nn; ++a)
        for (int w = 0; w < 4; ++w) mask[w] |= used[m.conn[e * m.nn + a]][w];
      int c = -1;
      for (int w = 0; w < 4 && c < 0; ++w)
        if (~mask[w]) c = 64 * w + __builtin_ctzll(~mask[w]);
      if (c < 0) c = 255;  // cannot happen for valid tetrahedral meshes (< 256 elements per node pair set)
      color[e] = c;
      ncolor = std::max(ncolor, c + 1);
      for (int a = 0; a < m.nn; ++a) used[m.conn[e * m.nn + a]][c / 64] |= uint64_t{1} << (c % 64);
    }
    m.colors.assign(ncolor, {});
    for (size_t e = 0; e < ne; ++e) m.colors[color[e]].push_back(static_cast<int>(e));
  }

  // Top surface: boundary faces of the corner mesh lying on z = z_top.
  const double tol = o.boundary_tolerance + 1e-9 * diag;
  m.z_top = hi.z();
  m.node_area.assign(nnode, 0.0);
  std::vector<double> node_h(nnode, std::numeric_limits<double>::infinity());
  {
    std::vector<std::pair<std::array<int, 3>, std::pair<int, int>>> faces;  // sorted corners, (tet, face)
    faces.reserve(ne * 4);
    static constexpr int fv[4][3] = {{0, 1, 2}, {1, 2, 3}, {2, 3, 0}, {3, 0, 1}};
    for (size_t e = 0; e < ne; ++e)
      for (int f = 0; f < 4; ++f) {
        std::array<int, 3> key{mesh.tets[e][fv[f][0]], mesh.tets[e][fv[f][1]], mesh.tets[e][fv[f][2]]};
        std::sort(key.begin(), key.end());
        faces.push_back({key, {static_cast<int>(e), f}});
      }
    std::sort(faces.begin(), faces.end());
    std::vector<char> is_top(nnode, 0);
    for (size_t i = 0; i < faces.size(); ++i) {
      const bool dup = (i > 0 && faces[i].first == faces[i - 1].first) ||
                       (i + 1 < faces.size() && faces[i].first == faces[i + 1].first);
      if (dup) continue;
      const auto& k = faces[i].first;
      if (std::abs(mesh.nodes[k[0]].z() - m.z_top) > tol || std::abs(mesh.nodes[k[1]].z() - m.z_top) > tol ||
          std::abs(mesh.nodes[k[2]].z() - m.z_top) > tol)
        continue;
      const double area = 0.5 * (mesh.nodes[k[1]] - mesh.nodes[k[0]]).cross(mesh.nodes[k[2]] - mesh.nodes[k[0]]).norm();
      const double h = std::sqrt(2 * area);
      const int e = faces[i].second.first;
      std::vector<int> face_nodes(k.begin(), k.end());
      if (m.nn == 10) {
        for (int c = 0; c < 3; ++c) m.node_area[k[c]] += area / 12;  // T6 face: corners A/12, mid-edges A/4
        for (int ed = 0; ed < 6; ++ed) {
          const int a = mesh.tets[e][detail::tet_edges[ed][0]], b = mesh.tets[e][detail::tet_edges[ed][1]];
          if (std::count(k.begin(), k.end(), a) && std::count(k.begin(), k.end(), b)) {
            const int mid = m.conn[static_cast<size_t>(e) * 10 + 4 + ed];
            m.node_area[mid] += area / 4;
            face_nodes.push_back(mid);
          }
        }
      } else {
        for (int c = 0; c < 3; ++c) m.node_area[k[c]] += area / 3;
      }
      for (int n : face_nodes) {
        is_top[n] = 1;
        node_h[n] = std::min(node_h[n], h);
      }
    }
    for (int n = 0; n < nnode; ++n)
      if (is_top[n]) m.top_nodes.push_back(n);
  }
  check(!m.top_nodes.empty(), "tissue mesh: no boundary faces on the top surface z = " + str(m.z_top) + " m");
  m.h_min = std::numeric_limits<double>::infinity();
  m.node_stiffness.assign(nnode, 0.0);
  for (int n : m.top_nodes) {
    m.h_min = std::min(m.h_min, node_h[n]);
    m.node_stiffness[n] = o.penalty_factor * node_e[n] / node_h[n] * m.node_area[n];
  }

  // Needles.
  check(!indenters.empty(), "indentation: no needle given");
  for (size_t k = 0; k < indenters.size(); ++k) {
    auto& ind = indenters[k];
    const std::string name = "needle " + str(k + 1);
    check(!ind.surface.vertices.empty() && !ind.surface.triangles.empty(), name + ": empty surface mesh");
    check(ind.direction.norm() > 0 && ind.direction.allFinite(), name + ": direction must be a non-zero vector");
    NeedleState nd;
    nd.direction = ind.direction.normalized();
    double zmin = std::numeric_limits<double>::infinity();
    for (const auto& v : ind.surface.vertices) zmin = std::min(zmin, v.z());
    check(zmin >= m.z_top - tol, name + " starts inside the tissue: its lowest point is at z = " + str(zmin) +
          " m, below the top surface z = " + str(m.z_top) + " m");
    if (o.contact == ContactModel::TipNodes) {
      check((nd.direction - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9,
            name + ": the tip-nodes contact model needs the direction (0, 0, -1)");
      nd.gap = zmin - m.z_top;
      // Flat tip face: triangles at the lowest level facing down.
      const double ntol = 1e-6 * (hi - lo).norm() + 1e-9;
      std::vector<std::array<Eigen::Vector2d, 3>> tip;
      for (const auto& t : ind.surface.triangles) {
        const auto &a = ind.surface.vertices[t[0]], &b = ind.surface.vertices[t[1]], &c = ind.surface.vertices[t[2]];
        if (a.z() > zmin + ntol || b.z() > zmin + ntol || c.z() > zmin + ntol) continue;
        const Eigen::Vector3d n = (b - a).cross(c - a);
        if (n.norm() == 0 || n.normalized().z() > -0.999) continue;
        tip.push_back({a.head<2>(), b.head<2>(), c.head<2>()});
      }
      std::vector<char> taken(nnode, 0);
      for (int n : m.top_nodes) {
        const Eigen::Vector2d p = m.nodes[n].head<2>();
        for (const auto& t : tip) {
          const Eigen::Vector2d e1 = t[1] - t[0], e2 = t[2] - t[0], w = p - t[0];
          const double det = e1.x() * e2.y() - e1.y() * e2.x();
          const double s = (w.x() * e2.y() - w.y() * e2.x()) / det, r = (e1.x() * w.y() - e1.y() * w.x()) / det;
          const double eps = 1e-7;
          if (s >= -eps && r >= -eps && s + r <= 1 + eps) {
            nd.tip_nodes.push_back(n);
            break;
          }
        }
      }
      if (nd.tip_nodes.empty()) {  // sharp tip: the top node nearest to the apex
        Eigen::Vector2d apex = Eigen::Vector2d::Zero();
        for (const auto& v : ind.surface.vertices)
          if (v.z() <= zmin + ntol) {
            apex = v.head<2>();
            break;
          }
        int best = m.top_nodes[0];
        for (int n : m.top_nodes)
          if ((m.nodes[n].head<2>() - apex).norm() < (m.nodes[best].head<2>() - apex).norm()) best = n;
        nd.tip_nodes.push_back(best);
      }
    } else {
      double hmax = -std::numeric_limits<double>::infinity();
      for (const auto& v : ind.surface.vertices) hmax = std::max(hmax, v.dot(nd.direction));
      nd.gap = std::max(0.0, -m.z_top * nd.direction.z() - hmax);  // rough: exact only for -z
      nd.distance = std::make_unique<detail::RigidSurfaceDistance>(ind.surface, nd.direction);
      nd.lambda.assign(m.top_nodes.size(), 0.0);
      nd.gap_now.assign(m.top_nodes.size(), std::numeric_limits<double>::infinity());
      nd.force_now.assign(m.top_nodes.size(), 0.0);
      nd.normal_now.assign(m.top_nodes.size(), Eigen::Vector3d::Zero());
      nd.ahead.assign(m.top_nodes.size(), 1);  // the needle starts above the tissue
    }
    nd.indenter = std::move(ind);
    m.needles.push_back(std::move(nd));
  }

  // Degrees of freedom: boundary conditions (§3.4: sides and bottom fixed, top free) and tip nodes.
  std::vector<char> fixed(m.ndof, 0);
  m.tip_dof.assign(m.ndof, 0);
  for (int n = 0; n < nnode; ++n) {
    const auto& p = m.nodes[n];
    const bool bottom = p.z() < lo.z() + tol;
    const bool side_x = p.x() < lo.x() + tol || p.x() > hi.x() - tol;
    const bool side_y = p.y() < lo.y() + tol || p.y() > hi.y() - tol;
    switch (o.boundary) {
      case BoundaryCondition::SidesAndBottomFixed:
        if (bottom || side_x || side_y) fixed[3 * n] = fixed[3 * n + 1] = fixed[3 * n + 2] = 1;
        break;
      case BoundaryCondition::BottomFixed:
        if (bottom) fixed[3 * n] = fixed[3 * n + 1] = fixed[3 * n + 2] = 1;
        break;
      case BoundaryCondition::BottomFixedSidesRoller:
        if (bottom) fixed[3 * n] = fixed[3 * n + 1] = fixed[3 * n + 2] = 1;
        if (side_x) fixed[3 * n] = 1;
        if (side_y) fixed[3 * n + 1] = 1;
        break;
      case BoundaryCondition::SymmetryPlanes:
        if (p.x() < lo.x() + tol) fixed[3 * n] = 1;
        if (p.y() < lo.y() + tol) fixed[3 * n + 1] = 1;
        if (bottom) fixed[3 * n + 2] = 1;
        break;
      case BoundaryCondition::QuarterSymmetry:
        if (p.x() < lo.x() + tol) fixed[3 * n] = 1;
        if (p.y() < lo.y() + tol) fixed[3 * n + 1] = 1;
        if (bottom || p.x() > hi.x() - tol || p.y() > hi.y() - tol) fixed[3 * n] = fixed[3 * n + 1] = fixed[3 * n + 2] = 1;
        break;
    }
  }
  if (o.contact == ContactModel::TipNodes)
    for (const auto& nd : m.needles)
      for (int a : nd.tip_nodes)
        if (!fixed[3 * a + 2]) m.tip_dof[3 * a + 2] = 1;
  m.free_index.assign(m.ndof, -1);
  for (int dof = 0; dof < m.ndof; ++dof)
    if (!fixed[dof] && !m.tip_dof[dof]) {
      m.free_index[dof] = static_cast<int>(m.free_dofs.size());
      m.free_dofs.push_back(dof);
    }
  check(!m.free_dofs.empty(), "tissue mesh: every degree of freedom is constrained");

  // Upper-triangular CSC pattern of the free-dof stiffness, from node adjacency.
  {
    m.pattern = detail::upper_pattern(m.conn, m.nn, nnode, m.free_index);
    m.values.assign(m.pattern.row_indices.size(), 0.0);
    m.rows32.assign(m.pattern.row_indices.begin(), m.pattern.row_indices.end());
    check(m.values.size() < static_cast<size_t>(std::numeric_limits<int32_t>::max()),
          "tissue mesh: the stiffness matrix has " + str(m.values.size()) + " entries, more than this solver indexes");
    const int k = 3 * m.nn;
    m.value_slot.assign(ne * static_cast<size_t>(k * k), -1);
    m.arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 1024), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t e = range.begin(); e < range.end(); ++e)
          for (int col = 0; col < k; ++col) {
            const int cb = m.free_index[3 * m.conn[e * m.nn + col / 3] + col % 3];
            if (cb < 0) continue;
            for (int row = 0; row < k; ++row) {
              const int ra = m.free_index[3 * m.conn[e * m.nn + row / 3] + row % 3];
              if (ra < 0 || ra > cb) continue;
              m.value_slot[e * k * k + col * k + row] =
                  static_cast<int32_t>(detail::entry_position(m.pattern, ra, cb));
            }
          }
      });
    });
  }
  m.linear_solver = o.linear_solver;
  if (m.linear_solver == LinearSolver::Automatic)
    m.linear_solver = coarse || m.nn == 10 ? LinearSolver::TwoGrid : LinearSolver::CholeskyCg;
  if (m.linear_solver == LinearSolver::TwoGrid)
    m.two_grid = std::make_unique<detail::TwoGridPreconditioner>(m.nn == 10 ? corners : *coarse, m.free_index, m.pattern);
  else
    m.cholesky = std::make_unique<detail::SparseCholesky>(static_cast<int64_t>(m.free_dofs.size()),
                                                          m.pattern.column_pointers, m.pattern.row_indices);

  m.u = Eigen::VectorXd::Zero(m.ndof);
  m.fint = Eigen::VectorXd::Zero(m.ndof);
  m.fcontact = Eigen::VectorXd::Zero(m.ndof);
  m.u_nodes.assign(nnode, Eigen::Vector3d::Zero());
  m.contact_flag.assign(nnode, 0);
  m.contact_pressure.assign(nnode, 0.0);
  m.last_force.assign(m.needles.size(), 0.0);
}

QuasiStaticSolver::~QuasiStaticSolver() = default;
QuasiStaticSolver::QuasiStaticSolver(QuasiStaticSolver&&) noexcept = default;
QuasiStaticSolver& QuasiStaticSolver::operator=(QuasiStaticSolver&&) noexcept = default;

StepResult QuasiStaticSolver::advance_to(double target) {
  auto& m = *impl_;
  const auto t0 = Clock::now();
  StepResult res;
  if (!std::isfinite(target)) {
    res.reason = "the target displacement is not finite";
    res.indenter_displacement = m.d;
    return res;
  }
  double step = target - m.d;
  int streak = 0;
  bool ok = true;
  while (ok && m.d != target) {
    const double next = std::abs(target - m.d) <= std::abs(step) * (1 + 1e-12) ? target : m.d + step;
    const Eigen::VectorXd u_saved = m.u;
    std::vector<std::vector<double>> lambda_saved;
    for (const auto& nd : m.needles) lambda_saved.push_back(nd.lambda);
    std::string why;
    if (m.substep(next, res, why, res.cutbacks)) {
      const double previous = m.d;
      m.d = next;
      m.last_increment = m.u - u_saved;
      m.last_step = next - previous;
      StepResult probe;
      m.measure(probe);
      for (size_t k = 0; k < m.needles.size(); ++k)
        m.external_work += 0.5 * (m.last_force[k] + probe.indenter_force[k]) * (next - previous);  // trapezoid
      m.last_force = probe.indenter_force;
      res.substeps++;
      if (++streak >= 2 && std::abs(step) < std::abs(target - m.d)) step *= 2, streak = 0;  // recover after cut-back
      if (std::abs(step) > std::abs(target - m.d) && m.d != target) step = target - m.d;
      continue;
    }
    m.u = u_saved;
    for (size_t k = 0; k < m.needles.size(); ++k) m.needles[k].lambda = lambda_saved[k];
    streak = 0;
    if (res.cutbacks >= m.opt.max_cutbacks) {
      res.reason = "stopped at " + fmt_um(m.d) + " (target " + fmt_um(target) + "): step to " + fmt_um(next) +
                   " failed after " + std::to_string(res.cutbacks) + " cut-backs: " + why;
      ok = false;
      break;
    }
    res.cutbacks++;
    step *= 0.5;
  }
  // Re-evaluate the converged state for the outputs.
  const auto ev = m.evaluate(m.u, m.d, true, false);
  m.measure(res);
  res.converged = ok;
  res.indenter_displacement = m.d;
  res.strain_energy = ev.strain_energy;
  res.external_work = m.external_work;
  for (int n = 0; n < static_cast<int>(m.u_nodes.size()); ++n) m.u_nodes[n] = m.u.segment<3>(3 * n);
  res.total_seconds = seconds_since(t0);
  return res;
}

double QuasiStaticSolver::indenter_displacement() const { return impl_->d; }
const std::vector<Eigen::Vector3d>& QuasiStaticSolver::nodes() const { return impl_->nodes; }
const std::vector<Eigen::Vector3d>& QuasiStaticSolver::displacement() const { return impl_->u_nodes; }
const std::vector<std::vector<int>>& QuasiStaticSolver::elements() const { return impl_->elements; }
const std::vector<int>& QuasiStaticSolver::contact_flag() const { return impl_->contact_flag; }
const std::vector<double>& QuasiStaticSolver::contact_pressure() const { return impl_->contact_pressure; }
const SolverOptions& QuasiStaticSolver::options() const { return impl_->opt; }
int QuasiStaticSolver::dof_count() const { return impl_->ndof; }
LinearSolver QuasiStaticSolver::linear_solver() const { return impl_->linear_solver; }
double QuasiStaticSolver::factor_nonzeros() const {
  return impl_->two_grid ? impl_->two_grid->coarse_factor_nonzeros() : impl_->cholesky->factor_nonzeros();
}
double QuasiStaticSolver::factor_flops() const {
  return impl_->two_grid ? impl_->two_grid->coarse_factor_flops() : impl_->cholesky->factor_flops();
}
int QuasiStaticSolver::free_dof_count() const { return static_cast<int>(impl_->free_dofs.size()); }

ElementFields QuasiStaticSolver::element_fields() const {
  const auto& m = *impl_;
  const size_t ne = m.elements.size();
  ElementFields out;
  out.cauchy_stress.resize(ne);
  out.von_mises_stress.resize(ne);
  out.strain_energy_density.resize(ne);
  out.volume_ratio.resize(ne);
  for (size_t e = 0; e < ne; ++e) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> ue(3, m.nn);
    for (int a = 0; a < m.nn; ++a) ue.col(a) = m.u.segment<3>(3 * m.conn[e * m.nn + a]);
    Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
    double w_sum = 0, energy = 0, jac = 0;
    for (int q = 0; q < m.nq; ++q) {
      const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> g(&m.grads[(e * m.nq + q) * 3 * m.nn], 3, m.nn);
      const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + ue * g.transpose();
      const auto s = stress_response(m.opt.law, m.lame[e], f, false);
      const double w = m.weights[e * m.nq + q];
      w_sum += w;
      jac += w * f.determinant();
      if (!s.valid) continue;
      sigma += w * cauchy_stress(f, s.second_piola_kirchhoff);
      energy += w * s.energy_density;
    }
    out.cauchy_stress[e] = sigma / w_sum;
    out.von_mises_stress[e] = von_mises_stress(out.cauchy_stress[e]);
    out.strain_energy_density[e] = energy / w_sum;
    out.volume_ratio[e] = jac / w_sum;
  }
  return out;
}

}  // namespace needlekit::fem
