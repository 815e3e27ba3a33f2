// Internal: the solution of the Newton systems K du = rhs on the assembled tangent (tangent_matrix.hpp), behind one
// interface. The built-in strategies: a CHOLMOD factorization per solve or CG on the last one
// (cholesky_solve.hpp), CG with a one-ring split preconditioner for the nodal-averaged tetrahedron
// (split_preconditioned_solve.hpp), and CG with the two-grid cycle (two_grid_solve.hpp). make_linear_solve chooses
// one from the resolved LinearSolver.
#pragma once
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "needlekit/fem/solver_options.hpp"
#include "tangent_matrix.hpp"

namespace needlekit::fem::detail {

class LinearSolve {
public:
  virtual ~LinearSolve() = default;
  // Solves K du = rhs (K: the tangent's current values) to the relative residual `forcing` (inexact Newton; never
  // tighter than SolverOptions::linear_tolerance). Records Krylov iterations and whether a factorization (or a
  // preconditioner's setup) was taken in `record`. False if K could not be solved.
  virtual bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, IterationRecord& record, double forcing) = 0;
  // Why solve() returned false, for the step's reason.
  virtual std::string failure_reason() const = 0;
  // Of the Cholesky factor in use (two-grid: the coarse level's): its entries and the flops of one factorization.
  virtual double factor_nonzeros() const = 0;
  virtual double factor_flops() const = 0;

  // Distributed assembly (the PETSc backend; the built-in strategies keep these defaults: one process assembles
  // everything). The assembly (quasi_static_solver.cpp) visits only the elements flagged here, per position of
  // TangentInputs::assembly_order (empty: all); its element sums (energy, internal force, the predictor's K_fp du_p)
  // are then partial and summed over the processes by sum_over_processes, the lowest inverted element found by
  // lowest_over_processes. Once the elements' tangent entries are in the matrix's values, and before the terms every
  // process adds alike (contact, the nodal average's patch term), it calls element_part_assembled.
  virtual const std::vector<char>& assembled_elements() const;
  // In place, the sums over the processes, the same values on every process.
  virtual void sum_over_processes(std::span<double> /*partial*/) {}
  virtual int lowest_over_processes(int value) { return value; }
  virtual void element_part_assembled() {}
};

// How the tangent must store the nodal average's patch term for `solver` (tangent_matrix.hpp); the PETSc backend
// leaves it to the product and takes the one-ring P of the element part and bulk term for GAMG.
TangentLayout tangent_layout(SolverBackend backend, LinearSolver solver, bool nodal_average);

// The strategy of options.backend and `solver` (resolved: not Automatic; the built-in backend's) on `matrix`, laid
// out by tangent_layout(options.backend, solver, ...). TwoGrid needs inputs.coarse.
std::unique_ptr<LinearSolve> make_linear_solve(LinearSolver solver, TangentMatrix& matrix, const TangentInputs& inputs,
                                               const SolverOptions& options, tbb::task_arena& arena);

}  // namespace needlekit::fem::detail
