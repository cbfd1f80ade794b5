// The momentum systems over MPI ranks; see distributed_helmholtz.hpp.
#include "cfd/parallel/distributed_helmholtz.hpp"

#include "cfd/flow/helmholtz_pcg.hpp"

namespace finverse::cfd {

DistributedHelmholtz::DistributedHelmholtz(const DistributedGrid& grid, const StretchedGrid& whole, FaceCoefficients beta,
                                           const BoundaryConditions& bc)
    : grid_(grid), op_(grid, whole, std::move(beta), bc) {
  work_ = {grid.make_field(1), grid.make_field(1), grid.make_field(1), grid.make_field(1)};
}

void DistributedHelmholtz::apply(double mass, double stiffness, Field& x, Field& out) const {
  op_.apply(x, out);
  add_mass(op_.block_operator(), mass, stiffness, x, out);
}

namespace {

struct RankHelmholtzOps {
  const DistributedHelmholtz& solver;
  const DistributedGrid& grid;
  double mass, stiffness;
  void apply(Field& x, Field& out) const { solver.apply(mass, stiffness, x, out); }
  void precondition(const Field& r, Field& z) const { jacobi(solver.op().block_operator(), mass, stiffness, r, z); }
  double dot(const Field& a, const Field& b) const { return grid.dot(a, b); }
  double norm2(const Field& a) const { return grid.norm2(a); }
};

}  // namespace

HelmholtzStats DistributedHelmholtz::solve(double mass, double stiffness, const Field& b, Field& x, double rtol,
                                           int max_iterations) {
  RankHelmholtzOps ops{*this, grid_, mass, stiffness};
  return helmholtz_pcg(ops, b, x, rtol, max_iterations, work_);
}

}  // namespace finverse::cfd
