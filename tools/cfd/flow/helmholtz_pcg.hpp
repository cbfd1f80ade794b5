// The Crank-Nicolson momentum systems' Jacobi-PCG (helmholtz_solver.hpp) written once over the
// operations it needs, so that the threaded solver and the solver on MPI ranks
// (cfd/parallel/distributed_helmholtz.hpp) take the same steps in the same order.
//
// Ops provides: apply(x, out) (out = (mass V + stiffness A) x), precondition(r, z) (the diagonal),
// dot(a, b), norm2(a).
#pragma once

#include <cmath>

#include "cfd/flow/helmholtz_solver.hpp"
#include "cfd/grid/field.hpp"

namespace finverse::cfd {

template <class Ops>
HelmholtzStats helmholtz_pcg(Ops& ops, const Field& b, Field& x, double rtol, int max_iterations, HelmholtzWork& w) {
  HelmholtzStats st;
  const double bnorm = ops.norm2(b);
  if (!std::isfinite(bnorm)) {  // a blown-up right-hand side: report, do not iterate on NaN
    st.relative_residual = bnorm;
    return st;
  }
  ops.apply(x, w.q);
  copy_interior(b, w.r);
  axpy(-1.0, w.q, w.r);
  double rn = ops.norm2(w.r);
  if (bnorm == 0 || rn <= rtol * bnorm) {
    st.converged = true;
    st.relative_residual = bnorm > 0 ? rn / bnorm : 0;
    return st;
  }
  double rz_old = 0;
  while (st.iterations < max_iterations) {
    ops.precondition(w.r, w.z);
    const double rz = ops.dot(w.r, w.z);
    if (st.iterations == 0) copy_interior(w.z, w.d);
    else xpby(w.z, rz / rz_old, w.d);
    rz_old = rz;
    ops.apply(w.d, w.q);
    const double dq = ops.dot(w.d, w.q);
    if (!(dq > 0)) break;
    const double alpha = rz / dq;
    axpy(alpha, w.d, x);
    axpy(-alpha, w.q, w.r);
    ++st.iterations;
    rn = ops.norm2(w.r);
    if (rn <= rtol * bnorm) break;
  }
  st.relative_residual = rn / bnorm;
  st.converged = st.relative_residual <= rtol;
  return st;
}

// The mass-plus-stiffness product and the Jacobi preconditioner on one operator's grid (a whole
// grid or a rank's block): out = mass V x + stiffness out_A, z = r / (mass V + stiffness diag).
void add_mass(const PoissonOperator& op, double mass, double stiffness, const Field& x, Field& out);
void jacobi(const PoissonOperator& op, double mass, double stiffness, const Field& r, Field& z);

}  // namespace finverse::cfd
