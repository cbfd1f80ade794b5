// Sparse direct coarsest-level solver; see coarse_solver.hpp.
#include "cfd/poisson/coarse_solver.hpp"

#include <stdexcept>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

namespace finverse::cfd {

struct CoarseSolver::Impl {
  const PoissonOperator* op = nullptr;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  std::vector<char> pinned;
  mutable Field work;
  mutable Eigen::VectorXd rhs, sol;
};

CoarseSolver::CoarseSolver() : impl_(std::make_unique<Impl>()) {}
CoarseSolver::~CoarseSolver() = default;
CoarseSolver::CoarseSolver(CoarseSolver&&) noexcept = default;
CoarseSolver& CoarseSolver::operator=(CoarseSolver&&) noexcept = default;

void CoarseSolver::setup(const PoissonOperator& op) {
  Impl& m = *impl_;
  m.op = &op;
  const StretchedGrid& g = op.grid();
  const int nx = g.nx(), ny = g.ny(), nz = g.nz();
  const auto n = static_cast<Eigen::Index>(g.cells());

  // One pinned cell per singular component: its first cell in storage order.
  m.pinned.assign(g.cells(), 0);
  std::vector<char> seen(static_cast<std::size_t>(op.components()), 0);
  for (std::size_t c = 0; c < g.cells(); ++c) {
    const int comp = op.component()[c];
    if (comp >= 0 && op.singular(comp) && !seen[static_cast<std::size_t>(comp)]) {
      seen[static_cast<std::size_t>(comp)] = 1;
      m.pinned[c] = 1;
    }
  }

  std::vector<Eigen::Triplet<double>> t;
  t.reserve(g.cells() * static_cast<std::size_t>(2 * op.dim() + 1));
  const FaceCoefficients& beta = op.beta();
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t c = op.cell_index(i, j, k);
        const auto row = static_cast<Eigen::Index>(c);
        if (!op.active(i, j, k) || m.pinned[c]) {
          t.emplace_back(row, row, 1.0);
          continue;
        }
        t.emplace_back(row, row, op.diagonal()[c]);
        const int idx[3] = {i, j, k}, nn[3] = {nx, ny, nz};
        for (int d = 0; d < op.dim(); ++d)
          for (int side = 0; side < 2; ++side) {
            int f[3] = {i, j, k};
            f[d] += side;
            const double tf = op.transmissibility(d)[beta.index(d, f[0], f[1], f[2])];
            if (tf == 0) continue;
            int nb[3] = {i, j, k};
            nb[d] = idx[d] + (side ? 1 : -1);
            if (nb[d] < 0 || nb[d] >= nn[d]) {
              if (!op.bc().periodic(d)) continue;
              nb[d] = (nb[d] + nn[d]) % nn[d];
            }
            const std::size_t cn = op.cell_index(nb[0], nb[1], nb[2]);
            if (m.pinned[cn]) continue;  // pinned value is zero: its column drops out
            t.emplace_back(row, static_cast<Eigen::Index>(cn), -tf);
          }
      }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());  // duplicates (periodic with n <= 2) are summed
  m.ldlt.compute(a);
  if (m.ldlt.info() != Eigen::Success)
    throw std::runtime_error("CoarseSolver: factorisation of the coarsest-level operator failed");
  m.work = op.make_field();
  m.rhs.resize(n);
  m.sol.resize(n);
}

void CoarseSolver::solve(const Field& b, Field& x) const {
  Impl& m = *impl_;
  const PoissonOperator& op = *m.op;
  const StretchedGrid& g = op.grid();
  copy_interior(b, m.work);
  op.remove_mean(m.work);
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const std::size_t c = op.cell_index(i, j, k);
        m.rhs[static_cast<Eigen::Index>(c)] = (m.pinned[c] || !op.active(i, j, k)) ? 0.0 : m.work(i, j, k);
      }
  m.sol = m.ldlt.solve(m.rhs);
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) x(i, j, k) = m.sol[static_cast<Eigen::Index>(op.cell_index(i, j, k))];
  op.remove_mean(x);
}

}  // namespace finverse::cfd
