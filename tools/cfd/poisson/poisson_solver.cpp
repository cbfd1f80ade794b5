// Multigrid cycles and multigrid-preconditioned conjugate gradients for the pressure Poisson
// equation; see poisson_solver.hpp.
#include "cfd/poisson/poisson_solver.hpp"

#include "cfd/poisson/mg_pcg.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace finverse::cfd {

namespace {
double poisson_seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

PoissonSystemFactory& flow_pressure_factory() {
  static PoissonSystemFactory factory;
  return factory;
}
}  // namespace

void install_flow_pressure_system(PoissonSystemFactory factory) { flow_pressure_factory() = std::move(factory); }

std::shared_ptr<PoissonSystemSolver> make_flow_pressure_system() {
  const PoissonSystemFactory& f = flow_pressure_factory();
  return f ? f() : nullptr;
}

void PoissonSolver::setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc,
                          const PoissonSolverOptions& options) {
  if (!(options.rtol > 0) || options.max_iterations < 1)
    throw std::invalid_argument("PoissonSolver: need rtol > 0 and max_iterations >= 1");
  const auto t0 = std::chrono::steady_clock::now();
  options_ = options;
  // A system solver handles the null space itself: this operator only assembles right-hand sides
  // and applies A (the ranks' solver builds its own blocks and components).
  op_.setup(grid, beta, bc, system_ ? PoissonOperator::Connectivity::Skip : PoissonOperator::Connectivity::Build);
  if (system_) {
    mg_ = Multigrid();
    system_->setup(op_, beta, options);
  } else {
    mg_.setup(op_, options.multigrid);
  }
  b_ = op_.make_field();
  work_ = {op_.make_field(), op_.make_field(), op_.make_field(), op_.make_field()};
  ++times_.setups;
  times_.setup_seconds += poisson_seconds_since(t0);
}

PoissonSolveStats PoissonSolver::solve(const Field& f, const BoundaryValues& values, Field& p) {
  if (f.nx() != b_.nx() || f.ny() != b_.ny() || f.nz() != b_.nz())
    throw std::invalid_argument("PoissonSolver::solve: f does not match the grid");
  op_.assemble_rhs(f, values, b_, rhs_lines());
  return solve_system(b_, p);
}

LineRange PoissonSolver::rhs_lines() const {
  const std::optional<LineRange> own = system_ ? system_->lines_read() : std::nullopt;
  return own ? *own : all_lines(op_.grid());
}

namespace {

// The threaded solver's operations for mg_pcg.hpp.
struct PoissonOps {
  const PoissonOperator& op;
  Multigrid& mg;
  void residual(const Field& b, Field& x, Field& r) const { op.residual(b, x, r); }
  void apply(Field& p, Field& out) const { op.apply(p, out); }
  void cycle(const Field& b, Field& x) const { mg.cycle(b, x); }
  double dot(const Field& a, const Field& b) const { return cfd::dot(a, b); }
  double norm2(const Field& a) const { return cfd::norm2(a); }
  void remove_mean(Field& f) const { op.remove_mean(f); }
  void make_compatible(Field& b) const { op.make_compatible(b); }
  void remove_volume_mean(Field& x) const { op.remove_volume_mean(x); }
  void zero_inactive(Field& f) const { op.zero_inactive(f); }
};

}  // namespace

PoissonSolveStats PoissonSolver::solve_system(Field& b, Field& x) {
  const auto t0 = std::chrono::steady_clock::now();
  PoissonSolveStats st;
  if (system_) {
    st = system_->solve_system(op_, b, x);
  } else {
    PoissonOps ops{op_, mg_};
    st = solve_poisson_system(ops, b, x, options_, work_);
  }
  ++times_.solves;
  times_.solve_seconds += poisson_seconds_since(t0);
  return st;
}

}  // namespace finverse::cfd
