// Multigrid cycles and multigrid-preconditioned conjugate gradients for the pressure Poisson
// equation; see poisson_solver.hpp.
#include "cfd/poisson/poisson_solver.hpp"

#include <cmath>
#include <stdexcept>

namespace finverse::cfd {

void PoissonSolver::setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc,
                          const PoissonSolverOptions& options) {
  if (!(options.rtol > 0) || options.max_iterations < 1)
    throw std::invalid_argument("PoissonSolver: need rtol > 0 and max_iterations >= 1");
  options_ = options;
  op_.setup(grid, beta, bc);
  mg_.setup(op_, options.multigrid);
  b_ = op_.make_field();
  r_ = op_.make_field();
  z_ = op_.make_field();
  q_ = op_.make_field();
  d_ = op_.make_field();
}

PoissonSolveStats PoissonSolver::solve(const Field& f, const BoundaryValues& values, Field& p) {
  if (f.nx() != b_.nx() || f.ny() != b_.ny() || f.nz() != b_.nz())
    throw std::invalid_argument("PoissonSolver::solve: f does not match the grid");
  op_.assemble_rhs(f, values, b_);
  return solve_system(b_, p);
}

PoissonSolveStats PoissonSolver::solve_system(Field& b, Field& x) {
  op_.zero_inactive(b);
  op_.make_compatible(b);
  op_.zero_inactive(x);
  const double bnorm = norm2(b);
  PoissonSolveStats st;
  st.rhs_norm = bnorm;
  if (bnorm == 0) {
    // The only solution with zero mean on singular components is zero.
    x.fill(0.0);
    st.converged = true;
    st.history.push_back(0);
    return st;
  }
  st = options_.method == PoissonMethod::MultigridPCG ? pcg(b, x, bnorm) : cycles(b, x, bnorm);
  op_.remove_volume_mean(x);
  st.rhs_norm = bnorm;
  st.relative_residual = st.history.back() / bnorm;
  st.initial_residual = st.history.front();
  st.convergence_factor =
      st.iterations > 0 && st.history.front() > 0
          ? std::pow(st.history.back() / st.history.front(), 1.0 / st.iterations)
          : 0.0;
  return st;
}

// Stand-alone multigrid: x <- x + MG(b - A x) until the residual is small enough. The residual is
// recomputed from scratch each cycle, so it is the true one.
PoissonSolveStats PoissonSolver::cycles(const Field& b, Field& x, double bnorm) {
  PoissonSolveStats st;
  op_.residual(b, x, r_);
  double rn = norm2(r_);
  st.history.push_back(rn);
  while (rn > options_.rtol * bnorm && st.iterations < options_.max_iterations) {
    mg_.cycle(b, x);
    op_.residual(b, x, r_);
    rn = norm2(r_);
    st.history.push_back(rn);
    ++st.iterations;
  }
  st.converged = rn <= options_.rtol * bnorm;
  return st;
}

// Preconditioned conjugate gradients with one multigrid cycle (from a zero guess) as the
// preconditioner. On singular components residual and preconditioned residual are kept in the
// range of A (mean removed), so CG never builds up a null-space component. Every 50 iterations the
// residual is recomputed from x to stop drift of the recursively updated one.
PoissonSolveStats PoissonSolver::pcg(const Field& b, Field& x, double bnorm) {
  PoissonSolveStats st;
  op_.residual(b, x, r_);
  op_.remove_mean(r_);
  double rn = norm2(r_);
  st.history.push_back(rn);
  if (rn <= options_.rtol * bnorm) {
    st.converged = true;
    return st;
  }
  double rz_old = 0;
  while (st.iterations < options_.max_iterations) {
    z_.fill(0.0);
    mg_.cycle(r_, z_);
    op_.remove_mean(z_);
    const double rz = dot(r_, z_);
    if (st.iterations == 0) copy_interior(z_, d_);
    else xpby(z_, rz / rz_old, d_);  // d = z + (rz/rz_old) d
    rz_old = rz;
    op_.apply(d_, q_);
    const double dq = dot(d_, q_);
    if (!(dq > 0)) break;  // breakdown: the preconditioned operator lost definiteness
    const double alpha = rz / dq;
    axpy(alpha, d_, x);
    ++st.iterations;
    if (st.iterations % 50 == 0) op_.residual(b, x, r_);
    else axpy(-alpha, q_, r_);
    op_.remove_mean(r_);
    rn = norm2(r_);
    st.history.push_back(rn);
    if (rn <= options_.rtol * bnorm) break;
  }
  // Report the true residual, not the recursively updated one.
  op_.residual(b, x, r_);
  op_.remove_mean(r_);
  st.history.back() = norm2(r_);
  st.converged = st.history.back() <= options_.rtol * bnorm;
  return st;
}

}  // namespace finverse::cfd
