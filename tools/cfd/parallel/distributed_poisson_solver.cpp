// The pressure Poisson solve over MPI ranks; see distributed_poisson_solver.hpp. The steps
// follow PoissonSolver's (poisson_solver.cpp) one for one.
#include "cfd/parallel/distributed_poisson_solver.hpp"

#include <mpi.h>

#include <cmath>

#include "cfd/poisson/mg_pcg.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

DistributedPoissonSolver::DistributedPoissonSolver(MPI_Comm comm, const StretchedGrid& whole, const BlockBeta& beta,
                                                   const BoundaryConditions& bc, const PoissonSolverOptions& options)
    : options_(options), whole_(whole) {
  if (!(options.rtol > 0) || options.max_iterations < 1) throw Error("distributed Poisson solver: need rtol > 0 and max_iterations >= 1");
  bc.validate();
  int ranks = 0;
  MPI_Comm_size(comm, &ranks);
  hierarchy_ = whole_hierarchy(whole_, bc, options.multigrid);
  const MultigridSplit split = plan_multigrid_split(hierarchy_, ranks);
  const int dim = whole_.dim();
  grid_ = std::make_unique<DistributedGrid>(comm, split.fine, std::array<bool, 3>{false, bc.periodic(1), dim == 3 && bc.periodic(2)});
  const Block& b = grid_->block();
  const StretchedGrid block_grid = whole_.block(b.j0, b.j1, b.k0, b.k1);
  op_ = std::make_unique<DistributedPoisson>(*grid_, whole_, beta(block_grid, b), bc);
  mg_ = std::make_unique<DistributedMultigrid>(*op_, hierarchy_, split.gathered_level, options.multigrid);
  components_ = std::make_unique<DistributedComponents>(*op_);
  int singular = 0;
  for (int c = 0; c < components_->components(); ++c) singular += components_->singular(c);
  if (singular > 1)
    throw Error("distributed Poisson solver: " + std::to_string(singular) +
                " singular (all-Neumann) components; across MPI ranks one is supported (give the domain a Dirichlet side)");
  long long counts[2] = {static_cast<long long>(op_->block_operator().active_cells()),
                         static_cast<long long>(op_->block_operator().grid().cells())};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG_LONG, MPI_SUM, comm);
  active_cells_ = counts[0], cells_ = counts[1];
  work_ = {grid_->make_field(1), grid_->make_field(1), grid_->make_field(1), grid_->make_field(1)};
}

DistributedPoissonSolver::~DistributedPoissonSolver() = default;

double DistributedPoissonSolver::singular_sum(const Field* x, bool volume_weight) const {
  const StretchedGrid& g = op_->block_grid();
  const auto& comp = *components_;
  const Field& shape = x ? *x : work_.r;  // the block's shape only, when summing the weights
  return grid_->line_sum(shape, [&](int j, int k) {
    double s = 0;
    for (int i = 0; i < g.nx(); ++i) {
      const int c = comp.component(i, j, k);
      if (c < 0 || !comp.singular(c)) continue;
      const double w = volume_weight ? g.volume(i, j, k) : 1.0;
      s += x ? w * (*x)(i, j, k) : w;
    }
    return s;
  });
}

// PoissonOperator::remove_mean: with one component the lane sums of field.hpp, line-ordered (the
// serial bits); with more, the singular component's line-ordered sum.
void DistributedPoissonSolver::remove_mean(Field& r) const {
  if (!components_->any_singular()) return;
  const StretchedGrid& g = op_->block_grid();
  const int nx = g.nx();
  const auto& comp = *components_;
  double mean = 0;
  if (comp.components() == 1) {
    const bool all = active_cells_ == cells_;
    mean = grid_->line_sum(r, [&](int j, int k) {
             const double* p = &r(0, j, k);
             if (all) return lane_sum(nx, [&](int i) { return p[i]; });
             return lane_sum(nx, [&](int i) { return comp.component(i, j, k) == 0 ? p[i] : 0.0; });
           }) /
           static_cast<double>(active_cells_);
  } else {
    const double n = singular_sum(nullptr, false);
    mean = n > 0 ? singular_sum(&r, false) / n : 0;
  }
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < nx; ++i) {
        const int c = comp.component(i, j, k);
        r(i, j, k) -= c >= 0 && comp.singular(c) ? mean : 0.0;
      }
}

void DistributedPoissonSolver::make_compatible(Field& b) const {
  if (!components_->any_singular()) return;
  const StretchedGrid& g = op_->block_grid();
  const double s = singular_sum(&b, false), v = singular_sum(nullptr, true);
  const double shift = v > 0 ? s / v : 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const int c = components_->component(i, j, k);
        if (c >= 0 && components_->singular(c)) b(i, j, k) -= shift * g.volume(i, j, k);
      }
}

void DistributedPoissonSolver::remove_volume_mean(Field& p) const {
  if (!components_->any_singular()) return;
  const StretchedGrid& g = op_->block_grid();
  const double s = singular_sum(&p, true), v = singular_sum(nullptr, true);
  const double shift = v > 0 ? s / v : 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const int c = components_->component(i, j, k);
        if (c >= 0 && components_->singular(c)) p(i, j, k) -= shift;
      }
}

namespace {

// The ranks' operations for mg_pcg.hpp.
struct RankPoissonOps {
  const DistributedPoissonSolver& solver;
  const DistributedPoisson& op;
  const DistributedGrid& grid;
  DistributedMultigrid& mg;
  void residual(const Field& b, Field& x, Field& r) const { op.residual(b, x, r); }
  void apply(Field& p, Field& out) const { op.apply(p, out); }
  void cycle(const Field& b, Field& x) const { mg.cycle(b, x); }
  double dot(const Field& a, const Field& b) const { return grid.dot(a, b); }
  double norm2(const Field& a) const { return grid.norm2(a); }
  void remove_mean(Field& f) const { solver.remove_mean(f); }
  void make_compatible(Field& b) const { solver.make_compatible(b); }
  void remove_volume_mean(Field& x) const { solver.remove_volume_mean(x); }
  void zero_inactive(Field& f) const { op.block_operator().zero_inactive(f); }
};

}  // namespace

PoissonSolveStats DistributedPoissonSolver::solve_system(Field& b, Field& x) {
  RankPoissonOps ops{*this, *op_, *grid_, *mg_};
  return solve_poisson_system(ops, b, x, options_, work_);
}

}  // namespace finverse::cfd
