// QuasiStaticSolver: construction (function space, boundary conditions, needles, tangent and its linear solve), the threaded
// element assembly and the outputs of the converged state. The load steps are in newton_step.cpp.
#include "needlekit/fem/quasi_static_solver.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>

#include "needlekit/core/errors.hpp"
#include "morton_order.hpp"
#include "quasi_static_solver_impl.hpp"
#include "tet_kernel.hpp"

namespace needlekit::fem {

namespace {

// Volumetric term on the nodal volume ratios (nodal_volume.hpp) of linear tetrahedron e: force V_e p̄_e J_e h_b and
// tangent V_e p̄_e J_e (h_b h_c^T - h_c h_b^T); the patch term is added after the element loop.
void add_nodal_volume_terms(const detail::NodalVolumeAverage& nodal, int e, double volume, bool want_tangent,
                            Eigen::Matrix<double, 3, 4>& fe, Eigen::Matrix<double, 12, 12>& ke) {
  const double pv = nodal.element_pressure(e) * volume;
  const Eigen::Matrix<double, 3, 4>& jh = nodal.element_jh(e);
  fe += pv * jh;
  if (!want_tangent) return;
  const double scale = pv / nodal.element_volume_ratio(e);
  for (int b = 0; b < 4; ++b)
    for (int cc = 0; cc < 4; ++cc)
      ke.template block<3, 3>(3 * b, 3 * cc) +=
          scale * (jh.col(b) * jh.col(cc).transpose() - jh.col(cc) * jh.col(b).transpose());
}

// Coupling of an element's free dofs to the prescribed tip dofs: the linear predictor's right-hand side K_fp du_p.
template <int N>
void add_prescribed_coupling(const int* c, const std::vector<int>& free_index,
                             const Eigen::Matrix<double, 3 * N, 3 * N>& ke, const Eigen::VectorXd& dup,
                             Eigen::VectorXd& kdup) {
  for (int a = 0; a < N; ++a)
    for (int i = 0; i < 3; ++i) {
      const int ra = free_index[3 * c[a] + i];
      if (ra < 0) continue;
      for (int b = 0; b < N; ++b)
        for (int j = 0; j < 3; ++j) {
          const int dofb = 3 * c[b] + j;
          if (free_index[dofb] < 0) kdup[ra] += ke(3 * a + i, 3 * b + j) * dup[dofb];
        }
    }
}

// An element's strain energy alone (no force, no tangent) added to `energy`; false if it is inverted.
template <int N>
bool add_element_energy(MaterialLaw law, const LameConstants& lame, const Eigen::Matrix<double, 3, N>& ue,
                        const detail::Grad<N>* g, const double* w, int nq, const Eigen::Matrix3d& initial_gradient,
                        double& energy) {
  bool valid = true;
  for (int q = 0; q < nq; ++q) {
    const Eigen::Matrix3d f = initial_gradient + ue * g[q].transpose();
    const auto s = stress_response(law, lame, f, false);
    if (!s.valid) valid = false;
    else energy += w[q] * s.energy_density;
  }
  return valid;
}

}  // namespace

// ---- assembly -------------------------------------------------------------------------------------------------
template <int N>
QuasiStaticSolver::Impl::Eval QuasiStaticSolver::Impl::element_pass(const Eigen::VectorXd& uu, bool want_force,
                                                                    bool want_tangent, const Eigen::VectorXd* dup,
                                                                    Eigen::VectorXd* kdup) {
  // Energy summed per block of a colour and then over the blocks in order (not per thread): the same sum whatever the
  // number of threads. Forces and tangent are deterministic anyway: within a colour no two blocks share a node, and
  // a block's elements are taken in order (element_colouring.hpp).
  const detail::ElementColouring& colouring = space.colouring;
  std::vector<double> block_energy;
  double strain_energy = 0;
  // The lowest-numbered inverted element (an atomic minimum: the same whatever the threads); none: the state is valid.
  std::atomic<int> first_inverted{std::numeric_limits<int>::max()};
  const auto record_inverted = [&](int e) {
    for (int now = first_inverted.load(); e < now && !first_inverted.compare_exchange_weak(now, e);) {
    }
  };
  const int nq = space.points;
  const auto& free_index = dofs.free_index;
  const std::vector<char>& assembled_here = linear_solve->assembled_elements();  // empty: every element
  if (want_force) fint.setZero(ndof);
  if (want_tangent) tangent->zero();
  std::vector<double>& values = tangent->values();
  for (size_t colour = 0; colour < colouring.colours(); ++colour) {
    const size_t first_block = colouring.colour_begin[colour];
    block_energy.assign(colouring.colour_begin[colour + 1] - first_block, 0.0);
    arena.execute([&] {
      tbb::parallel_for(size_t{0}, block_energy.size(), [&](size_t block) {
        Eigen::Matrix<double, 3, N> ue, fe;
        Eigen::Matrix<double, 3 * N, 3 * N> ke;
        double& en = block_energy[block];
        size_t position = colouring.block_begin[first_block + block];  // in the assembly order
        for (const int e : colouring.block(first_block + block)) {
          const size_t at = position++;
          if (!assembled_here.empty() && !assembled_here[at]) continue;  // another process's element
          const int* c = &space.assembly.connectivity[at * N];
          for (int a = 0; a < N; ++a) ue.col(a) = uu.segment<3>(3 * c[a]);
          const auto* g =
              reinterpret_cast<const detail::Grad<N>*>(&space.assembly.gradients[at * static_cast<size_t>(nq * 3 * N)]);
          const double* w = &space.assembly.weights[at * static_cast<size_t>(nq)];
          const Eigen::Matrix3d f0 = space.assembly.initial_gradient.empty() ? Eigen::Matrix3d::Identity()
                                                                             : space.assembly.initial_gradient[at];
          if (!want_force) {  // energy only
            if (!add_element_energy<N>(opt.law, space.lame[e], ue, g, w, nq, f0, en)) record_inverted(e);
            continue;
          }
          double we;
          const bool ok = detail::tet_kernel<N>(g, w, nq, opt.law, space.lame[e], ue, we, fe,
                                                want_tangent ? &ke : nullptr, f0);
          if (!ok) {
            record_inverted(e);
            continue;
          }
          if constexpr (N == 4) {
            if (nodal && nodal->treated(e)) add_nodal_volume_terms(*nodal, e, space.volumes[e], want_tangent, fe, ke);
          }
          en += we;
          for (int a = 0; a < N; ++a) fint.segment<3>(3 * c[a]) += fe.col(a);
          if (!want_tangent) continue;
          const int32_t* slot = tangent->element_slots(at);
          for (int col = 0; col < 3 * N; ++col)
            for (int row = 0; row <= col; ++row, ++slot)
              if (*slot >= 0) values[static_cast<size_t>(*slot)] += ke(row, col);
          if (kdup) add_prescribed_coupling<N>(c, free_index, ke, *dup, *kdup);
        }
      });
    });
    for (double e : block_energy) strain_energy += e;
  }
  Eval ev;
  ev.strain_energy = strain_energy;
  ev.valid = first_inverted == std::numeric_limits<int>::max();
  if (!ev.valid) ev.inverted_element = first_inverted;
  return ev;
}

QuasiStaticSolver::Impl::Eval QuasiStaticSolver::Impl::evaluate(const Eigen::VectorXd& uu, double disp,
                                                                bool want_force, bool want_tangent,
                                                                const Eigen::VectorXd* dup, Eigen::VectorXd* kdup) {
  double volumetric_energy = 0;
  if (nodal && !nodal->update(uu, want_tangent, volumetric_energy, arena)) {
    Eval inverted;
    inverted.valid = false;
    inverted.inverted_element = nodal->inverted_element();
    return inverted;
  }
  Eval ev = space.nodes_per_element == 4 ? element_pass<4>(uu, want_force, want_tangent, dup, kdup)
                                         : element_pass<10>(uu, want_force, want_tangent, dup, kdup);
  if (!linear_solve->assembled_elements().empty()) sum_element_parts(ev, want_force, kdup);
  if (ev.valid && want_tangent) linear_solve->element_part_assembled();
  ev.strain_energy += volumetric_energy;
  if (ev.valid && contact)
    ev.contact_energy = contact->evaluate(space.nodes, uu, disp, want_force, want_tangent, fcontact,
                                          dofs.free_index, tangent->pattern(), tangent->values());
  if (ev.valid && start_share != 0)
    for (size_t k = 0; k < dofs.free_dofs.size(); ++k)
      ev.load_energy -= start_share * start_residual[static_cast<Eigen::Index>(k)] * uu[dofs.free_dofs[k]];
  if (ev.valid && nodal && want_tangent) {
    if (tangent->splits_preconditioner()) {  // P: everything so far (one-ring) plus the element bulk term
      tangent->capture_preconditioner();
      add_bulk_preconditioner();
    }
    if (tangent->stores_patch_term())
      nodal->add_patch_tangent(dofs.free_index, tangent->pattern(), tangent->values(), arena);
    if (kdup) nodal->add_prescribed_coupling(dofs.free_index, *dup, *kdup);
  }
  return ev;
}

void QuasiStaticSolver::Impl::sum_element_parts(Eval& ev, bool want_force, Eigen::VectorXd* kdup) {
  // Every process takes part in every sum, whether or not it found an inverted element.
  ev.inverted_element = linear_solve->lowest_over_processes(ev.valid ? std::numeric_limits<int>::max()
                                                                     : ev.inverted_element);
  ev.valid = ev.inverted_element == std::numeric_limits<int>::max();
  if (!ev.valid) return;
  linear_solve->sum_over_processes({&ev.strain_energy, 1});
  if (want_force) linear_solve->sum_over_processes({fint.data(), static_cast<size_t>(fint.size())});
  if (kdup) linear_solve->sum_over_processes({kdup->data(), static_cast<size_t>(kdup->size())});
}

void QuasiStaticSolver::Impl::add_bulk_preconditioner() {
  std::vector<double>& pre = tangent->preconditioner_values();
  const detail::ElementColouring& colouring = space.colouring;
  for (size_t colour = 0; colour < colouring.colours(); ++colour)  // within a colour no two blocks share an entry
    arena.execute([&] {
      tbb::parallel_for(colouring.colour_begin[colour], colouring.colour_begin[colour + 1], [&](size_t block) {
        size_t position = colouring.block_begin[block];  // in the assembly order
        for (const int e : colouring.block(block)) {
          const size_t at = position++;
          if (!nodal->treated(e)) continue;
          const double scale = nodal->element_bulk_curvature(e) * space.volumes[static_cast<size_t>(e)];
          if (scale == 0) continue;
          const Eigen::Matrix<double, 3, 4>& jh = nodal->element_jh(e);
          const int32_t* slot = tangent->element_slots(at);
          for (int col = 0; col < 12; ++col)
            for (int row = 0; row <= col; ++row, ++slot)
              if (*slot >= 0)
                pre[static_cast<size_t>(tangent->preconditioner_slot(*slot))] +=
                    scale * jh(row % 3, row / 3) * jh(col % 3, col / 3);
        }
      });
    });
}

QuasiStaticSolver::Impl::Failure QuasiStaticSolver::Impl::inverted(const Eval& ev) const {
  if (ev.inverted_element < 0) return {StepStatus::InvertedElement, "an element inverted (J <= 0)"};
  const int e = ev.inverted_element;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int a = 0; a < 4; ++a) centre += space.nodes[static_cast<size_t>(space.elements[static_cast<size_t>(e)][a])] / 4;
  const double um = 1e6;
  std::ostringstream s;
  s.precision(4);
  s << "tetrahedron " << e << " inverted (J <= 0); its centre at (" << centre.x() * um << ", " << centre.y() * um
    << ") um, " << (space.box_max.z() - centre.z()) * um << " um below the top surface (reference positions)";
  return {StepStatus::InvertedElement, s.str()};
}

Eigen::VectorXd QuasiStaticSolver::Impl::free_residual() const {
  Eigen::VectorXd r(static_cast<Eigen::Index>(dofs.free_dofs.size()));
  for (size_t k = 0; k < dofs.free_dofs.size(); ++k)
    r[static_cast<Eigen::Index>(k)] = fint[dofs.free_dofs[k]] - (contact ? fcontact[dofs.free_dofs[k]] : 0.0);
  if (start_share != 0) r -= start_share * start_residual;
  return r;
}

void QuasiStaticSolver::Impl::add_free(Eigen::VectorXd& uu, const Eigen::VectorXd& du, double alpha) const {
  for (size_t k = 0; k < dofs.free_dofs.size(); ++k)
    uu[dofs.free_dofs[k]] += alpha * du[static_cast<Eigen::Index>(k)];
}

void QuasiStaticSolver::Impl::measure(StepResult& res) {
  const size_t m = needles.size();
  res.indenter_force.assign(m, 0);
  res.contact_force.assign(m, Eigen::Vector3d::Zero());
  res.contact_moment.assign(m, Eigen::Vector3d::Zero());
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
      const double p = top.node_area[a] > 0 ? force / top.node_area[a] : 0;
      contact_flag[a] = static_cast<int>(k) + 1;
      contact_pressure[a] = p;
      res.indenter_force[k] += force;
      res.contact_area[k] += top.node_area[a];
      res.contact_nodes[k]++;
      res.max_contact_pressure[k] = any ? std::max(res.max_contact_pressure[k], p) : p;
      any = true;
    };
    if (opt.contact == ContactModel::TipNodes) {
      if (d > nd.gap)
        for (int a : nd.tip_nodes)
          if (dofs.tip_dof[3 * a + 2]) {
            const double axial = fint.segment<3>(3 * a).dot(nd.direction);  // Eq 3.11
            record(a, axial);
            const Eigen::Vector3d at = space.nodes[a] + u.segment<3>(3 * a) - d * nd.direction;
            res.contact_moment[k] -= at.cross(axial * nd.direction);
          }
    } else {
      for (size_t t = 0; t < top.nodes.size(); ++t)
        if (contact->node_force(k, t) > 0) record(top.nodes[t], contact->axial_force(k, t));
      res.indenter_force[k] += contact->edge_axial_force(k);  // the second pass: force only, no nodal area
      res.contact_force[k] = contact->force_on_needle(k);
      res.contact_moment[k] = contact->moment_on_needle(k);
    }
    if (opt.contact == ContactModel::TipNodes) res.contact_force[k] = -res.indenter_force[k] * nd.direction;
    if (res.contact_area[k] > 0) res.mean_contact_pressure[k] = res.indenter_force[k] / res.contact_area[k];
  }
  res.max_penetration = contact ? contact->max_penetration() : 0.0;
}

double QuasiStaticSolver::Impl::smallest_volume_ratio() const {
  const int nn = space.nodes_per_element, nq = space.points;
  double smallest = std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 3, Eigen::Dynamic> ue(3, nn);
  for (size_t e = 0; e < space.elements.size(); ++e) {
    for (int a = 0; a < nn; ++a) ue.col(a) = u.segment<3>(3 * space.connectivity[e * nn + a]);
    for (int q = 0; q < nq; ++q) {
      const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> g(&space.gradients[(e * nq + q) * 3 * nn], 3,
                                                                          nn);
      smallest = std::min(smallest, (space.initial(e) + ue * g.transpose()).determinant());
    }
  }
  return smallest;
}

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

// A coarse level that interpolates every node of the mesh from nodes it has.
void check_coarse_level(const mesh::CoarseLevel& coarse, const mesh::TetMesh& mesh) {
  check(coarse.interpolation.size() == mesh.nodes.size(),
        "coarse level: " + str(coarse.interpolation.size()) + " interpolated nodes for " + str(mesh.nodes.size()) +
            " nodes");
  for (const mesh::NodeInterpolation& parents : coarse.interpolation)
    for (int k = 0; k < 4; ++k) {
      const int a = parents.nodes[static_cast<size_t>(k)];
      if (a < -1 || a >= coarse.nodes || (a == -1 && parents.weights[static_cast<size_t>(k)] != 0))
        throw InvalidInput("coarse level: parent node " + str(a) + " outside [0, " + str(coarse.nodes) + ")");
    }
}

// The nodal-averaged volume on the linear tetrahedra of the layers it applies to; none when no layer needs it.
std::unique_ptr<detail::NodalVolumeAverage> nodal_average(const mesh::TetMesh& mesh, detail::FunctionSpace& space,
                                                          const SolverOptions& o) {
  std::vector<char> treated(mesh.tets.size(), 0);
  bool any = false;
  for (size_t e = 0; e < mesh.tets.size(); ++e) {
    treated[e] = nodal_average_applies(o, mesh.layers[mesh.tet_layer[e]].poisson_ratio);
    any = any || treated[e];
  }
  if (!any) return nullptr;
  return std::make_unique<detail::NodalVolumeAverage>(space, treated, o.volumetric_stabilization);
}

}  // namespace

// One needle checked (a surface, a direction, an edge radius for surface contact only, above the tissue) with its
// gap and tip nodes for the tip-nodes contact model.
QuasiStaticSolver::Impl::Needle QuasiStaticSolver::Impl::placed_needle(Indenter ind, const std::string& name,
                                                                      const SolverOptions& o,
                                                                      const detail::TopSurface& top,
                                                                      const detail::FunctionSpace& space, double tol) {
  check(!ind.surface.vertices.empty() && !ind.surface.triangles.empty(), name + ": empty surface mesh");
  check(ind.direction.norm() > 0 && ind.direction.allFinite(), name + ": direction must be a non-zero vector");
  Needle nd;
  nd.direction = ind.direction.normalized();
  check(std::isfinite(ind.edge_radius) && ind.edge_radius >= 0,
        name + ": edge radius " + str(ind.edge_radius) + " m, expected a finite length >= 0");
  check(ind.edge_radius == 0 || o.contact == ContactModel::Surface,
        name + ": an edge radius applies to surface contact only (the tip-nodes rule takes the tip face as flat)");
  double zmin = std::numeric_limits<double>::infinity();
  for (const auto& v : ind.surface.vertices) zmin = std::min(zmin, v.z() - ind.edge_radius);
  check(zmin >= top.z - tol, name + " starts inside the tissue: its lowest point is at z = " + str(zmin) +
        " m, below the top surface z = " + str(top.z) + " m");
  if (o.contact == ContactModel::TipNodes) {
    check((nd.direction - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9,
          name + ": the tip-nodes contact model needs the direction (0, 0, -1)");
    nd.gap = zmin - top.z;
    const Eigen::Vector3d extent = space.box_max - space.box_min;
    nd.tip_nodes = detail::tip_nodes(top, space, ind.surface, 1e-6 * extent.norm() + 1e-9);
  }
  nd.indenter = std::move(ind);
  return nd;
}

QuasiStaticSolver::QuasiStaticSolver(const mesh::TetMesh& mesh, std::vector<Indenter> indenters, SolverOptions options,
                                     const mesh::CoarseLevel* coarse)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  m.opt = std::move(options);
  const auto& o = m.opt;
  o.validate();
  check(o.linear_solver != LinearSolver::TwoGrid || coarse || o.order == ElementOrder::Quadratic,
        "solver linear_solver = \"two-grid\" needs a coarse level for linear elements: a mesh split from a coarser "
        "one (mesh::refine_uniformly; [mesh] split = true in a case file) or the body meshed again at twice the sizes "
        "(mesh::interpolating_coarse_level; a case file's block gets one)");
  if (coarse && o.order == ElementOrder::Linear) check_coarse_level(*coarse, mesh);
  m.arena.initialize(o.threads > 0 ? o.threads : tbb::task_arena::automatic);

  detail::validate_tissue_mesh(mesh);
  m.space = detail::function_space(mesh, o.order);
  const auto& lo = m.space.box_min;
  const auto& hi = m.space.box_max;
  const int nnode = static_cast<int>(m.space.nodes.size());
  m.ndof = 3 * nnode;
  const double tol = o.boundary_tolerance + 1e-9 * (hi - lo).norm();
  m.top = detail::top_surface(mesh, m.space, tol);

  // Needles.
  check(!indenters.empty(), "indentation: no needle given");
  for (size_t k = 0; k < indenters.size(); ++k) {
    m.needles.push_back(Impl::placed_needle(std::move(indenters[k]), "needle " + str(k + 1), o, m.top, m.space, tol));
  }
  if (o.contact == ContactModel::Surface) {
    std::vector<Indenter> placed;
    for (const auto& nd : m.needles) placed.push_back(nd.indenter);
    m.contact = std::make_unique<detail::SurfaceContact>(m.top, m.space, placed, o);
    m.embedding = std::make_unique<detail::NeedleEmbedding>(m.space, m.top, placed, m.contact->smallest_size() / 2);
  }

  // Degrees of freedom: boundary conditions (§3.4: sides and bottom fixed, top free) and tip nodes.
  std::vector<std::vector<int>> tips;
  for (const auto& nd : m.needles) tips.push_back(nd.tip_nodes);
  m.dofs = detail::dof_map(detail::fixed_dofs(m.space, o.boundary, tol), tips,
                           detail::morton_order(m.space.nodes, m.space.box_min, m.space.box_max));
  check(!m.dofs.free_dofs.empty(), "tissue mesh: every degree of freedom is constrained");

  // Linear tetrahedra near incompressibility: the volumetric term on nodal-averaged volume ratios.
  if (nodal_average_possible(o)) m.nodal = nodal_average(mesh, m.space, o);
  LinearSolver solver = o.linear_solver;
  if (solver == LinearSolver::Automatic)
    solver = coarse || m.space.nodes_per_element == 10 ? LinearSolver::TwoGrid : LinearSolver::CholeskyCg;
  m.solver = solver;
  const detail::TangentInputs inputs{m.space.connectivity, m.space.nodes_per_element, nnode, m.space.nodes,
                                     m.dofs.free_index, m.space.colouring.elements, m.nodal.get(),
                                     m.space.nodes_per_element == 10 ? &m.space.corners : coarse};
  m.tangent = std::make_unique<detail::TangentMatrix>(
      inputs, detail::tangent_layout(o.backend, solver, m.nodal != nullptr), m.arena);
  m.linear_solve = detail::make_linear_solve(solver, *m.tangent, inputs, m.opt, m.arena);

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

// ---- outputs --------------------------------------------------------------------------------------------------
double QuasiStaticSolver::indenter_displacement() const { return impl_->d; }
const std::vector<Eigen::Vector3d>& QuasiStaticSolver::nodes() const { return impl_->space.nodes; }
const std::vector<Eigen::Vector3d>& QuasiStaticSolver::displacement() const { return impl_->u_nodes; }
const std::vector<std::vector<int>>& QuasiStaticSolver::elements() const { return impl_->space.elements; }
// The top-surface nodes' contact multipliers and friction states, and the second pass's multipliers with each tissue
// face named by its top nodes (a rezoning renumbers the faces but keeps the top surface's nodes and faces).
struct QuasiStaticSolver::ContactHistory {
  std::vector<Eigen::Vector3d> top_nodes;  // m, reference positions, in the order of the history's vectors
  detail::SurfaceContact::Multipliers multipliers;
  std::vector<std::vector<detail::NeedleEdgeContact::HeldPair>> held_pairs;
};

std::shared_ptr<const QuasiStaticSolver::ContactHistory> QuasiStaticSolver::contact_history() const {
  if (!impl_->contact) return nullptr;
  auto history = std::make_shared<ContactHistory>();
  for (int n : impl_->top.nodes) history->top_nodes.push_back(impl_->space.nodes[static_cast<size_t>(n)]);
  history->multipliers = impl_->contact->multipliers();
  history->held_pairs = impl_->contact->held_pairs();
  return history;
}

bool QuasiStaticSolver::set_contact_history(const ContactHistory& history) {
  if (!impl_->contact || history.top_nodes.size() != impl_->top.nodes.size()) return false;
  for (size_t t = 0; t < history.top_nodes.size(); ++t)
    if (history.top_nodes[t] != impl_->space.nodes[static_cast<size_t>(impl_->top.nodes[t])]) return false;
  detail::SurfaceContact::Multipliers multipliers = impl_->contact->multipliers();
  if (multipliers.nodes.size() != history.multipliers.nodes.size()) return false;
  multipliers.nodes = history.multipliers.nodes;
  multipliers.friction = history.multipliers.friction;
  impl_->contact->set_multipliers(multipliers);
  impl_->contact->set_held_pairs(history.held_pairs);
  return true;
}

const std::vector<int>& QuasiStaticSolver::contact_flag() const { return impl_->contact_flag; }
const std::vector<double>& QuasiStaticSolver::contact_pressure() const { return impl_->contact_pressure; }
const std::vector<double>& QuasiStaticSolver::top_node_area() const { return impl_->top.node_area; }
const SolverOptions& QuasiStaticSolver::options() const { return impl_->opt; }
int QuasiStaticSolver::dof_count() const { return impl_->ndof; }
LinearSolver QuasiStaticSolver::linear_solver() const { return impl_->solver; }
double QuasiStaticSolver::factor_nonzeros() const { return impl_->linear_solve->factor_nonzeros(); }
double QuasiStaticSolver::factor_flops() const { return impl_->linear_solve->factor_flops(); }
int QuasiStaticSolver::nodal_average_elements() const { return impl_->nodal ? impl_->nodal->element_count() : 0; }

QuasiStaticSolver::Linearization QuasiStaticSolver::linearization(const std::vector<Eigen::Vector3d>& u,
                                                                  double indenter_displacement) {
  auto& m = *impl_;
  Eigen::VectorXd uu(m.ndof);
  for (size_t n = 0; n < u.size() && 3 * n < static_cast<size_t>(m.ndof); ++n) uu.segment<3>(3 * n) = u[n];
  Linearization out;
  if (m.contact) m.contact->set_positive_curvature(false);
  const Impl::Eval ev = m.evaluate(uu, indenter_displacement, true, true);
  out.valid = ev.valid;
  out.energy = ev.potential();
  // The solver numbers the free dofs in its own order; the outputs take them in ascending dof order.
  const Eigen::VectorXd gradient = m.free_residual();
  const Eigen::Index n = static_cast<Eigen::Index>(m.dofs.free_dofs.size());
  std::vector<Eigen::Index> ascending(static_cast<size_t>(n));  // per free index: its position in the outputs
  for (int dof = 0, position = 0; dof < m.ndof; ++dof)
    if (m.dofs.free_index[dof] >= 0) ascending[static_cast<size_t>(m.dofs.free_index[dof])] = position++;
  out.gradient.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) out.gradient[ascending[static_cast<size_t>(k)]] = gradient[k];
  const auto& pattern = m.tangent->pattern();
  const auto& values = m.tangent->values();
  out.tangent = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    const Eigen::Index col = ascending[static_cast<size_t>(c)];
    for (int64_t k = pattern.column_pointers[c]; k < pattern.column_pointers[c + 1]; ++k) {
      const Eigen::Index r = ascending[static_cast<size_t>(pattern.row_indices[k])];
      out.tangent(r, col) = out.tangent(col, r) = values[static_cast<size_t>(k)];
    }
  }
  if (m.nodal && !m.tangent->stores_patch_term())
    m.nodal->add_patch_tangent(m.dofs.free_index, ascending, out.tangent);
  return out;
}
int QuasiStaticSolver::free_dof_count() const { return static_cast<int>(impl_->dofs.free_dofs.size()); }

ElementFields QuasiStaticSolver::element_fields() const {
  const auto& m = *impl_;
  const auto& sp = m.space;
  const int nn = sp.nodes_per_element, nq = sp.points;
  const size_t ne = sp.elements.size();
  ElementFields out;
  out.cauchy_stress.resize(ne);
  out.von_mises_stress.resize(ne);
  out.strain_energy_density.resize(ne);
  out.volume_ratio.resize(ne);
  for (size_t e = 0; e < ne; ++e) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> ue(3, nn);
    for (int a = 0; a < nn; ++a) ue.col(a) = m.u.segment<3>(3 * sp.connectivity[e * nn + a]);
    Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
    double w_sum = 0, energy = 0, jac = 0;
    for (int q = 0; q < nq; ++q) {
      const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> g(&sp.gradients[(e * nq + q) * 3 * nn], 3, nn);
      const Eigen::Matrix3d f = sp.initial(e) + ue * g.transpose();
      const auto s = stress_response(m.opt.law, sp.lame[e], f, false);
      const double w = sp.weights[e * nq + q];
      w_sum += w;
      jac += w * f.determinant();
      if (!s.valid) continue;
      sigma += w * cauchy_stress(f, s.second_piola_kirchhoff);
      energy += w * s.energy_density;
    }
    if (m.nodal && m.nodal->treated(static_cast<int>(e))) {
      // The averaged volumetric part: Cauchy pressure p̄_e = mean U'(J̄) of the element's nodes (its stored energy
      // lives at the nodes and is left out of the element's density).
      sigma += w_sum * m.nodal->element_pressure(static_cast<int>(e)) * Eigen::Matrix3d::Identity();
    }
    out.cauchy_stress[e] = sigma / w_sum;
    out.von_mises_stress[e] = von_mises_stress(out.cauchy_stress[e]);
    out.strain_energy_density[e] = energy / w_sum;
    out.volume_ratio[e] = jac / w_sum;
  }
  return out;
}

}  // namespace needlekit::fem
