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
  // The singular component's volume, summed once: make_compatible and remove_volume_mean divide by it.
  if (components_->any_singular()) singular_volume_ = singular_sum(nullptr, true);
}

DistributedPoissonSolver::~DistributedPoissonSolver() = default;

double DistributedPoissonSolver::singular_sum(const Field* x, bool volume_weight) const {
  const StretchedGrid& g = op_->block_grid();
  const auto& comp = *components_;
  const Field& shape = x ? *x : work_.r;  // the block's shape only, when summing the weights
  return grid_->line_sum(shape, [&](int j, int k) {
    const int* c = comp.line(j, k);
    const double* p = x ? &(*x)(0, j, k) : nullptr;
    double s = 0;
    for (int i = 0; i < g.nx(); ++i) {
      if (c[i] < 0 || !comp.singular(c[i])) continue;
      const double w = volume_weight ? g.volume(i, j, k) : 1.0;
      s += p ? w * p[i] : w;
    }
    return s;
  });
}

// Subtracts shift (times the cell's volume with volume_weight) in the singular component's cells.
// One component is the usual case (a body's cells are -1): a select that vectorises, as
// PoissonOperator's; subtracting 0 leaves a value's bits as they are.
void DistributedPoissonSolver::shift_singular(Field& f, double shift, bool volume_weight) const {
  const StretchedGrid& g = op_->block_grid();
  const auto& comp = *components_;
  const int nx = g.nx();
  const bool one = comp.components() == 1;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j) {
      const int* c = comp.line(j, k);
      double* p = &f(0, j, k);
      if (one && !volume_weight) {
        for (int i = 0; i < nx; ++i) p[i] -= c[i] == 0 ? shift : 0.0;
        continue;
      }
      for (int i = 0; i < nx; ++i)
        if (c[i] >= 0 && comp.singular(c[i])) p[i] -= volume_weight ? shift * g.volume(i, j, k) : shift;
    }
}

// PoissonOperator::remove_mean: with one component the lane sums of field.hpp, line-ordered (the
// serial bits); with more, the singular component's line-ordered sum.
void DistributedPoissonSolver::remove_mean(Field& r) const {
  if (!components_->any_singular()) return;
  const int nx = op_->block_grid().nx();
  const auto& comp = *components_;
  double mean = 0;
  if (comp.components() == 1) {
    const bool all = active_cells_ == cells_;
    mean = grid_->line_sum(r, [&](int j, int k) {
             const double* p = &r(0, j, k);
             if (all) return lane_sum(nx, [&](int i) { return p[i]; });
             const int* c = comp.line(j, k);
             return lane_sum(nx, [&](int i) { return c[i] == 0 ? p[i] : 0.0; });
           }) /
           static_cast<double>(active_cells_);
  } else {
    const double n = singular_sum(nullptr, false);
    mean = n > 0 ? singular_sum(&r, false) / n : 0;
  }
  shift_singular(r, mean, false);
}

void DistributedPoissonSolver::make_compatible(Field& b) const {
  if (!components_->any_singular()) return;
  const double s = singular_sum(&b, false);
  shift_singular(b, singular_volume_ > 0 ? s / singular_volume_ : 0, true);
}

void DistributedPoissonSolver::remove_volume_mean(Field& p) const {
  if (!components_->any_singular()) return;
  const double s = singular_sum(&p, true);
  shift_singular(p, singular_volume_ > 0 ? s / singular_volume_ : 0, false);
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
