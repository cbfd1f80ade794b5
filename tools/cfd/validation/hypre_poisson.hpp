// The Poisson benchmark problem (poisson_bench_problem.hpp) solved by hypre, the peer of finverse's
// MG-PCG in fin-poisson-bench: hypre's structured multigrid PFMG and BoomerAMG, each preconditioning
// CG, to the same relative residual (two-norm). The matrix is finverse's PoissonOperator's
// (transmissibilities and diagonal), so both codes solve the same linear system; masked cells get an
// identity row. hypre wants a nonsingular matrix, so the first cell of the all-Neumann matrix is
// pinned (p = 0, its row and column the identity's): with a compatible right-hand side the solution
// differs only by the constant. Each MPI rank holds a slab of z-planes. Built only with hypre and
// MPI (tools/apps/cfd.cmake: finverse_cfd_hypre).
#pragma once

#include <string>
#include <vector>

namespace finverse::cfd::validation {

struct HypreRun {
  std::string solver;  // PFMG-PCG or BoomerAMG-PCG
  double setup_s = 0, solve_s = 0, relative_residual = 0;
  int iterations = 0;
  bool converged = false;
};

// The benchmark problem on n cells per axis (maximum stretch ratio `ratio`, a sphere masked out when
// `mask`) solved on MPI_COMM_WORLD (this process is `rank` of `ranks`) with PFMG, then BoomerAMG.
// MPI and hypre are initialised by the caller.
std::vector<HypreRun> solve_poisson_bench_with_hypre(int n, double ratio, bool mask, double rtol, int rank, int ranks);

}  // namespace finverse::cfd::validation
