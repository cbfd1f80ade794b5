// Times the sparse solver backends on the tangent of a beam lattice, and sparse LU of the full
// matrix (the study docs/studies/fem_sparse_solver.md):
//   fem_solver_bench [nodes per side, default 90 -> ~48k DOFs]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "fem/assembly.hpp"
#include "fem/sparse_solver.hpp"
#include "fem_test_models.hpp"

using namespace finverse::fem;

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 90;
  const Model m = test::lattice(n);
  const DofMap dofs(m);
  Assembler a(m, dofs);
  AssemblyRequest req;
  req.matrix = true;
  auto now = [] { return std::chrono::steady_clock::now(); };
  auto sec = [](auto t0, auto t1) { return std::chrono::duration<double>(t1 - t0).count(); };
  auto t0 = now();
  a.assemble(m.reference_state(), req);
  std::printf("lattice %dx%d: %d free DOFs, %ld upper nonzeros, assembly %.4f s\n", n, n,
              dofs.free(), static_cast<long>(a.matrix().nonZeros()), sec(t0, now()));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(dofs.free());
  for (auto backend : {SolverBackend::cholmod, SolverBackend::simplicial_ldlt}) {
    SparseSolver s(backend);
    auto t1 = now();
    s.factorize(a.matrix());  // analysis + numeric
    auto t2 = now();
    const int repeats = 3;
    for (int r = 0; r < repeats; ++r) s.factorize(a.matrix());  // numeric only (pattern reused)
    auto t3 = now();
    Eigen::VectorXd x = s.solve(b);
    auto t4 = now();
    const Eigen::VectorXd res =
        Assembler::SparseMatrix(a.matrix().selfadjointView<Eigen::Upper>()) * x - b;
    std::printf("%-16s first (analyse+factor) %.3f s, refactor %.3f s, solve %.4f s, "
                "symbolic analyses %d, rel. residual %.1e\n",
                to_string(backend), sec(t1, t2), sec(t2, t3) / repeats, sec(t3, t4),
                s.symbolic_count(), res.norm() / b.norm());
  }
  // Sparse LU of the full (non-symmetric, StaticOptions::unsymmetric_tangent) matrix.
  Assembler full(m, dofs, true);
  full.assemble(m.reference_state(), req);
  for (auto backend : {SolverBackend::sparse_lu, SolverBackend::umfpack}) {
    SparseSolver lu(backend);
    auto t1 = now();
    lu.factorize(full.matrix());
    auto t2 = now();
    lu.factorize(full.matrix());
    auto t3 = now();
    const Eigen::VectorXd x = lu.solve(b);
    auto t4 = now();
    std::printf("%-16s first (analyse+factor) %.3f s, refactor %.3f s, solve %.4f s, "
                "symbolic analyses %d, rel. residual %.1e\n",
                to_string(backend), sec(t1, t2), sec(t2, t3), sec(t3, t4), lu.symbolic_count(),
                (full.matrix() * x - b).norm() / b.norm());
  }
}
