// Exact solve on the coarsest multigrid level: sparse Cholesky (LDL^T) of the assembled operator.
//
// Inactive cells get an identity row. On each singular component (all-Neumann, no Dirichlet face)
// one cell is pinned to zero by removing its row and column; the remaining system is symmetric
// positive definite, and for a compatible right-hand side its solution satisfies the removed
// equation too. The right-hand side is first projected onto the range (mean removed per singular
// component) and the solution's mean removed afterwards, so the coarse solve acts as the
// pseudo-inverse on the range: a symmetric map, as a CG preconditioner needs.
#pragma once

#include <memory>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

class CoarseSolver {
 public:
  CoarseSolver();
  ~CoarseSolver();
  CoarseSolver(CoarseSolver&&) noexcept;
  CoarseSolver& operator=(CoarseSolver&&) noexcept;

  void setup(const PoissonOperator& op);
  // x = A^+ b (b is not modified).
  void solve(const Field& b, Field& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace finverse::cfd
