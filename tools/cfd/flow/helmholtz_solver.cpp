// Jacobi-preconditioned conjugate gradients for the Crank-Nicolson momentum systems; see
// helmholtz_solver.hpp for why this is the method of choice here.
#include "cfd/flow/helmholtz_solver.hpp"

#include <cmath>

namespace finverse::cfd {

void HelmholtzSolver::setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc) {
  op_.setup(grid, beta, bc);
  r_ = op_.make_field();
  z_ = op_.make_field();
  d_ = op_.make_field();
  q_ = op_.make_field();
}

void HelmholtzSolver::apply(double mass, double stiffness, Field& x, Field& out) const {
  op_.apply(x, out);
  const StretchedGrid& g = op_.grid();
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
  for (int l = 0; l < g.ny() * g.nz(); ++l) {
    const int j = l % g.ny(), k = l / g.ny();
    const double* px = &x(0, j, k);
    double* po = &out(0, j, k);
    const double ayz = g.dy(j) * g.dz(k);
    for (int i = 0; i < g.nx(); ++i) po[i] = mass * g.dx(i) * ayz * px[i] + stiffness * po[i];
  }
}

HelmholtzStats HelmholtzSolver::solve(double mass, double stiffness, const Field& b, Field& x, double rtol,
                                      int max_iterations) {
  const StretchedGrid& g = op_.grid();
  const auto& diag = op_.diagonal();
  const auto precondition = [&] {
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
    for (int l = 0; l < g.ny() * g.nz(); ++l) {
      const int j = l % g.ny(), k = l / g.ny();
      const double ayz = g.dy(j) * g.dz(k);
      const double* pr = &r_(0, j, k);
      double* pz = &z_(0, j, k);
      const std::size_t c0 = op_.cell_index(0, j, k);
      for (int i = 0; i < g.nx(); ++i) pz[i] = pr[i] / (mass * g.dx(i) * ayz + stiffness * diag[c0 + i]);
    }
  };
  HelmholtzStats st;
  const double bnorm = norm2(b);
  if (!std::isfinite(bnorm)) {  // a blown-up right-hand side: report, do not iterate on NaN
    st.relative_residual = bnorm;
    return st;
  }
  apply(mass, stiffness, x, q_);
  copy_interior(b, r_);
  axpy(-1.0, q_, r_);
  double rn = norm2(r_);
  if (bnorm == 0 || rn <= rtol * bnorm) {
    st.converged = true;
    st.relative_residual = bnorm > 0 ? rn / bnorm : 0;
    return st;
  }
  double rz_old = 0;
  while (st.iterations < max_iterations) {
    precondition();
    const double rz = dot(r_, z_);
    if (st.iterations == 0) copy_interior(z_, d_);
    else xpby(z_, rz / rz_old, d_);
    rz_old = rz;
    apply(mass, stiffness, d_, q_);
    const double dq = dot(d_, q_);
    if (!(dq > 0)) break;
    const double alpha = rz / dq;
    axpy(alpha, d_, x);
    axpy(-alpha, q_, r_);
    ++st.iterations;
    rn = norm2(r_);
    if (rn <= rtol * bnorm) break;
  }
  st.relative_residual = rn / bnorm;
  st.converged = st.relative_residual <= rtol;
  return st;
}

}  // namespace finverse::cfd
