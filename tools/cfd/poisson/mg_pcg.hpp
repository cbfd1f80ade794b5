// The pressure solve's iterations (PoissonSolver, poisson_solver.hpp), written once over the
// operations they need, so that the threaded solver and the solver on MPI ranks
// (cfd/parallel/distributed_poisson_solver.hpp) take the same steps in the same order and, where
// their operations give the same bits, the same iterates.
//
// Ops provides: residual(b, x, r), apply(p, out), cycle(b, x) (one multigrid cycle), dot(a, b),
// norm2(a), remove_mean(f), make_compatible(b), remove_volume_mean(x), zero_inactive(f).
#pragma once

#include <cmath>

#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_solver.hpp"

namespace finverse::cfd {

// Stand-alone multigrid: x <- x + MG(b - A x) until the residual is small enough. The residual is
// recomputed from scratch each cycle, so it is the true one.
template <class Ops>
PoissonSolveStats mg_cycles(Ops& ops, const Field& b, Field& x, double bnorm, const PoissonSolverOptions& o, SolveWork& w) {
  PoissonSolveStats st;
  ops.residual(b, x, w.r);
  double rn = ops.norm2(w.r);
  st.history.push_back(rn);
  while (rn > o.rtol * bnorm && st.iterations < o.max_iterations) {
    ops.cycle(b, x);
    ops.residual(b, x, w.r);
    rn = ops.norm2(w.r);
    st.history.push_back(rn);
    ++st.iterations;
  }
  st.converged = rn <= o.rtol * bnorm;
  return st;
}

// Preconditioned conjugate gradients with one multigrid cycle (from a zero guess) as the
// preconditioner. On singular components residual and preconditioned residual are kept in the
// range of A (mean removed), so CG never builds up a null-space component. Every 50 iterations the
// residual is recomputed from x to stop drift of the recursively updated one.
template <class Ops>
PoissonSolveStats mg_pcg(Ops& ops, const Field& b, Field& x, double bnorm, const PoissonSolverOptions& o, SolveWork& w) {
  PoissonSolveStats st;
  ops.residual(b, x, w.r);
  ops.remove_mean(w.r);
  double rn = ops.norm2(w.r);
  st.history.push_back(rn);
  if (rn <= o.rtol * bnorm) {
    st.converged = true;
    return st;
  }
  double rz_old = 0;
  while (st.iterations < o.max_iterations) {
    w.z.fill(0.0);
    ops.cycle(w.r, w.z);
    ops.remove_mean(w.z);
    const double rz = ops.dot(w.r, w.z);
    if (st.iterations == 0) copy_interior(w.z, w.d);
    else xpby(w.z, rz / rz_old, w.d);  // d = z + (rz/rz_old) d
    rz_old = rz;
    ops.apply(w.d, w.q);
    const double dq = ops.dot(w.d, w.q);
    if (!(dq > 0)) break;  // breakdown: the preconditioned operator lost definiteness
    const double alpha = rz / dq;
    axpy(alpha, w.d, x);
    ++st.iterations;
    if (st.iterations % 50 == 0) ops.residual(b, x, w.r);
    else axpy(-alpha, w.q, w.r);
    ops.remove_mean(w.r);
    rn = ops.norm2(w.r);
    st.history.push_back(rn);
    if (rn <= o.rtol * bnorm) break;
  }
  // Report the true residual, not the recursively updated one.
  ops.residual(b, x, w.r);
  ops.remove_mean(w.r);
  st.history.back() = ops.norm2(w.r);
  st.converged = st.history.back() <= o.rtol * bnorm;
  return st;
}

// A x = b with b made compatible in place, by the method the options name.
template <class Ops>
PoissonSolveStats solve_poisson_system(Ops& ops, Field& b, Field& x, const PoissonSolverOptions& o, SolveWork& w) {
  ops.zero_inactive(b);
  ops.make_compatible(b);
  ops.zero_inactive(x);
  const double bnorm = ops.norm2(b);
  PoissonSolveStats st;
  st.rhs_norm = bnorm;
  if (bnorm == 0) {
    // The only solution with zero mean on singular components is zero.
    x.fill(0.0);
    st.converged = true;
    st.history.push_back(0);
    return st;
  }
  st = o.method == PoissonMethod::MultigridPCG ? mg_pcg(ops, b, x, bnorm, o, w) : mg_cycles(ops, b, x, bnorm, o, w);
  ops.remove_volume_mean(x);
  st.rhs_norm = bnorm;
  st.relative_residual = st.history.back() / bnorm;
  st.initial_residual = st.history.front();
  st.convergence_factor =
      st.iterations > 0 && st.history.front() > 0 ? std::pow(st.history.back() / st.history.front(), 1.0 / st.iterations) : 0.0;
  return st;
}

}  // namespace finverse::cfd
