// The Poisson benchmark problem solved by hypre PFMG-PCG and BoomerAMG-PCG (hypre_poisson.hpp).
#include "cfd/validation/hypre_poisson.hpp"

#include <HYPRE.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <HYPRE_struct_ls.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstddef>

#include "cfd/poisson/poisson_operator.hpp"
#include "cfd/validation/poisson_bench_problem.hpp"

namespace finverse::cfd::validation {

namespace {

constexpr std::size_t kPinned = 0;  // cell (0,0,0): in the far field, never inside the body

// The 7-point stencil of cell (i,j,k): centre, -x, +x, -y, +y, -z, +z.
std::array<double, 7> stencil(const PoissonOperator& op, int i, int j, int k) {
  const auto& g = op.grid();
  const auto c = op.cell_index(i, j, k);
  if (op.diagonal()[c] <= 0 || c == kPinned) return {1, 0, 0, 0, 0, 0, 0};  // inactive or pinned: identity
  auto face = [&](int d, int fi, int fj, int fk) {
    const auto fx = static_cast<std::size_t>(g.nx() + (d == 0)), fy = static_cast<std::size_t>(g.ny() + (d == 1));
    const auto at =
        static_cast<std::size_t>(fi) + fx * (static_cast<std::size_t>(fj) + fy * static_cast<std::size_t>(fk));
    return op.transmissibility(d)[at];
  };
  std::array<double, 7> s{op.diagonal()[c], 0, 0, 0, 0, 0, 0};
  if (i > 0) s[1] = -face(0, i, j, k);
  if (i < g.nx() - 1) s[2] = -face(0, i + 1, j, k);
  if (j > 0) s[3] = -face(1, i, j, k);
  if (j < g.ny() - 1) s[4] = -face(1, i, j + 1, k);
  if (k > 0) s[5] = -face(2, i, j, k);
  if (k < g.nz() - 1) s[6] = -face(2, i, j, k + 1);
  // The pinned cell's column: p there is 0, so its coupling drops out (keeps A symmetric).
  if (c == kPinned + 1) s[1] = 0;
  if (c == kPinned + static_cast<std::size_t>(g.nx())) s[3] = 0;
  if (c == kPinned + static_cast<std::size_t>(g.nx()) * static_cast<std::size_t>(g.ny())) s[5] = 0;
  return s;
}

double wtime_since(double t0) {
  MPI_Barrier(MPI_COMM_WORLD);
  return MPI_Wtime() - t0;
}

HypreRun solve_pfmg(const PoissonOperator& op, const Field& b, int k0, int k1, double rtol) {
  const auto& g = op.grid();
  MPI_Barrier(MPI_COMM_WORLD);
  const double t0 = MPI_Wtime();
  HYPRE_StructGrid grid;
  HYPRE_StructGridCreate(MPI_COMM_WORLD, 3, &grid);
  HYPRE_Int lo[3] = {0, 0, k0}, hi[3] = {g.nx() - 1, g.ny() - 1, k1};
  HYPRE_StructGridSetExtents(grid, lo, hi);
  HYPRE_StructGridAssemble(grid);
  HYPRE_StructStencil st;
  HYPRE_StructStencilCreate(3, 7, &st);
  HYPRE_Int offsets[7][3] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int e = 0; e < 7; ++e) HYPRE_StructStencilSetElement(st, e, offsets[e]);
  HYPRE_StructMatrix A;
  HYPRE_StructMatrixCreate(MPI_COMM_WORLD, grid, st, &A);
  HYPRE_StructMatrixInitialize(A);
  const std::size_t ncell = static_cast<std::size_t>(g.nx()) * g.ny() * (k1 - k0 + 1);
  std::vector<double> values(7 * ncell), rhs(ncell), zero(ncell, 0.0);
  std::size_t m = 0;
  for (int k = k0; k <= k1; ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i, ++m) {
        const auto s = stencil(op, i, j, k);
        std::copy(s.begin(), s.end(), values.begin() + static_cast<std::ptrdiff_t>(7 * m));
        rhs[m] = b(i, j, k);
      }
  HYPRE_Int entries[7] = {0, 1, 2, 3, 4, 5, 6};
  HYPRE_StructMatrixSetBoxValues(A, lo, hi, 7, entries, values.data());
  HYPRE_StructMatrixAssemble(A);
  HYPRE_StructVector vb, vx;
  HYPRE_StructVectorCreate(MPI_COMM_WORLD, grid, &vb);
  HYPRE_StructVectorCreate(MPI_COMM_WORLD, grid, &vx);
  HYPRE_StructVectorInitialize(vb);
  HYPRE_StructVectorInitialize(vx);
  HYPRE_StructVectorSetBoxValues(vb, lo, hi, rhs.data());
  HYPRE_StructVectorSetBoxValues(vx, lo, hi, zero.data());
  HYPRE_StructVectorAssemble(vb);
  HYPRE_StructVectorAssemble(vx);

  HYPRE_StructSolver pcg, pfmg;
  HYPRE_StructPCGCreate(MPI_COMM_WORLD, &pcg);
  HYPRE_StructPCGSetTol(pcg, rtol);
  HYPRE_StructPCGSetTwoNorm(pcg, 1);
  HYPRE_StructPCGSetMaxIter(pcg, 500);
  HYPRE_StructPFMGCreate(MPI_COMM_WORLD, &pfmg);
  HYPRE_StructPFMGSetMaxIter(pfmg, 1);
  HYPRE_StructPFMGSetTol(pfmg, 0.0);
  HYPRE_StructPFMGSetZeroGuess(pfmg);
  HYPRE_StructPFMGSetRelaxType(pfmg, 2);  // symmetric red-black Gauss-Seidel, as ours
  HYPRE_StructPFMGSetNumPreRelax(pfmg, 1);
  HYPRE_StructPFMGSetNumPostRelax(pfmg, 1);
  HYPRE_StructPCGSetPrecond(pcg, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, pfmg);
  HYPRE_StructPCGSetup(pcg, A, vb, vx);
  HypreRun r{"PFMG-PCG"};
  r.setup_s = wtime_since(t0);
  const double t1 = MPI_Wtime();
  HYPRE_StructPCGSolve(pcg, A, vb, vx);
  r.solve_s = wtime_since(t1);
  HYPRE_Int its = 0;
  HYPRE_StructPCGGetNumIterations(pcg, &its);
  HYPRE_StructPCGGetFinalRelativeResidualNorm(pcg, &r.relative_residual);
  r.iterations = its;
  r.converged = r.relative_residual <= rtol;
  HYPRE_StructPFMGDestroy(pfmg);
  HYPRE_StructPCGDestroy(pcg);
  HYPRE_StructVectorDestroy(vb);
  HYPRE_StructVectorDestroy(vx);
  HYPRE_StructMatrixDestroy(A);
  HYPRE_StructStencilDestroy(st);
  HYPRE_StructGridDestroy(grid);
  return r;
}

HypreRun solve_boomeramg(const PoissonOperator& op, const Field& b, int k0, int k1, double rtol) {
  const auto& g = op.grid();
  const HYPRE_BigInt plane = static_cast<HYPRE_BigInt>(g.nx()) * g.ny();
  const HYPRE_BigInt lo = k0 * plane, hi = (k1 + 1) * plane - 1;
  MPI_Barrier(MPI_COMM_WORLD);
  const double t0 = MPI_Wtime();
  HYPRE_IJMatrix A;
  HYPRE_IJMatrixCreate(MPI_COMM_WORLD, lo, hi, lo, hi, &A);
  HYPRE_IJMatrixSetObjectType(A, HYPRE_PARCSR);
  std::vector<HYPRE_Int> row_sizes(static_cast<std::size_t>(hi - lo + 1), 7);
  HYPRE_IJMatrixSetRowSizes(A, row_sizes.data());
  HYPRE_IJMatrixInitialize(A);
  std::vector<double> rhs, zero;
  std::vector<HYPRE_BigInt> rows;
  for (int k = k0; k <= k1; ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const auto s = stencil(op, i, j, k);
        const HYPRE_BigInt row = static_cast<HYPRE_BigInt>(op.cell_index(i, j, k));
        const HYPRE_BigInt nb[7] = {row, row - 1, row + 1, row - g.nx(), row + g.nx(), row - plane, row + plane};
        HYPRE_BigInt cols[7];
        double vals[7];
        HYPRE_Int n = 0;
        for (int e = 0; e < 7; ++e)
          if (s[static_cast<std::size_t>(e)] != 0 || e == 0)
            cols[n] = nb[e], vals[n++] = s[static_cast<std::size_t>(e)];
        HYPRE_IJMatrixSetValues(A, 1, &n, &row, cols, vals);
        rows.push_back(row);
        rhs.push_back(b(i, j, k));
        zero.push_back(0.0);
      }
  HYPRE_IJMatrixAssemble(A);
  HYPRE_ParCSRMatrix parA;
  HYPRE_IJMatrixGetObject(A, reinterpret_cast<void**>(&parA));
  HYPRE_IJVector vb, vx;
  for (auto* v : {&vb, &vx}) {
    HYPRE_IJVectorCreate(MPI_COMM_WORLD, lo, hi, v);
    HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(*v);
  }
  HYPRE_IJVectorSetValues(vb, static_cast<HYPRE_Int>(rows.size()), rows.data(), rhs.data());
  HYPRE_IJVectorSetValues(vx, static_cast<HYPRE_Int>(rows.size()), rows.data(), zero.data());
  HYPRE_IJVectorAssemble(vb);
  HYPRE_IJVectorAssemble(vx);
  HYPRE_ParVector pb, px;
  HYPRE_IJVectorGetObject(vb, reinterpret_cast<void**>(&pb));
  HYPRE_IJVectorGetObject(vx, reinterpret_cast<void**>(&px));

  HYPRE_Solver pcg, amg;
  HYPRE_ParCSRPCGCreate(MPI_COMM_WORLD, &pcg);
  HYPRE_PCGSetTol(pcg, rtol);
  HYPRE_PCGSetTwoNorm(pcg, 1);
  HYPRE_PCGSetMaxIter(pcg, 500);
  HYPRE_BoomerAMGCreate(&amg);
  HYPRE_BoomerAMGSetMaxIter(amg, 1);
  HYPRE_BoomerAMGSetTol(amg, 0.0);
  HYPRE_BoomerAMGSetStrongThreshold(amg, 0.5);  // hypre's advice for 3-D Laplacians
  HYPRE_BoomerAMGSetCoarsenType(amg, 10);       // HMIS
  HYPRE_BoomerAMGSetInterpType(amg, 6);         // extended+i, the usual partner of HMIS
  HYPRE_BoomerAMGSetPMaxElmts(amg, 4);
  HYPRE_BoomerAMGSetRelaxType(amg, 8);  // l1-symmetric Gauss-Seidel: keeps PCG's SPD requirement
  HYPRE_BoomerAMGSetPrintLevel(amg, 0);
  HYPRE_PCGSetPrecond(pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                      reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
  HYPRE_ParCSRPCGSetup(pcg, parA, pb, px);
  HypreRun r{"BoomerAMG-PCG"};
  r.setup_s = wtime_since(t0);
  const double t1 = MPI_Wtime();
  HYPRE_ParCSRPCGSolve(pcg, parA, pb, px);
  r.solve_s = wtime_since(t1);
  HYPRE_Int its = 0;
  HYPRE_PCGGetNumIterations(pcg, &its);
  HYPRE_PCGGetFinalRelativeResidualNorm(pcg, &r.relative_residual);
  r.iterations = its;
  r.converged = r.relative_residual <= rtol;
  HYPRE_BoomerAMGDestroy(amg);
  HYPRE_ParCSRPCGDestroy(pcg);
  HYPRE_IJVectorDestroy(vb);
  HYPRE_IJVectorDestroy(vx);
  HYPRE_IJMatrixDestroy(A);
  return r;
}

}  // namespace

std::vector<HypreRun> solve_poisson_bench_with_hypre(int n, double ratio, bool mask, double rtol, int rank, int ranks) {
  const auto problem = make_poisson_bench_problem(n, ratio, mask);
  PoissonOperator op;
  op.setup(problem.grid, problem.beta, problem.bc);
  Field b = op.make_field();
  op.assemble_rhs(problem.source, BoundaryValues{}, b);
  op.make_compatible(b);
  b(0, 0, 0) = 0;  // the pinned cell
  const int nz = problem.grid.nz();
  const int k0 = rank * nz / ranks, k1 = (rank + 1) * nz / ranks - 1;
  HypreRun pfmg = solve_pfmg(op, b, k0, k1, rtol);
  HypreRun amg = solve_boomeramg(op, b, k0, k1, rtol);
  return {pfmg, amg};
}

}  // namespace finverse::cfd::validation
