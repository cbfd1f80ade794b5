// Jacobi-preconditioned conjugate gradients for the Crank-Nicolson momentum systems; see
// helmholtz_solver.hpp for why this is the method of choice here.
#include "cfd/flow/helmholtz_solver.hpp"

#include "cfd/flow/helmholtz_pcg.hpp"

#include <cmath>
#include <utility>

namespace finverse::cfd {

namespace {
HelmholtzSystemFactory& flow_momentum_factory() {
  static HelmholtzSystemFactory factory;
  return factory;
}
}  // namespace

void install_flow_momentum_system(HelmholtzSystemFactory factory) { flow_momentum_factory() = std::move(factory); }

std::shared_ptr<HelmholtzSystemSolver> make_flow_momentum_system() {
  const HelmholtzSystemFactory& f = flow_momentum_factory();
  return f ? f() : nullptr;
}

void HelmholtzSolver::setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc) {
  op_.setup(grid, beta, bc);
  if (system_) {
    work_ = {};
    system_->setup(op_, beta, bc);
  } else {
    work_ = {op_.make_field(), op_.make_field(), op_.make_field(), op_.make_field()};
  }
}

void add_mass(const PoissonOperator& op, double mass, double stiffness, const Field& x, Field& out) {
  const StretchedGrid& g = op.grid();
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
  for (int l = 0; l < g.ny() * g.nz(); ++l) {
    const int j = l % g.ny(), k = l / g.ny();
    const double* px = &x(0, j, k);
    double* po = &out(0, j, k);
    const double ayz = g.dy(j) * g.dz(k);
    for (int i = 0; i < g.nx(); ++i) po[i] = mass * g.dx(i) * ayz * px[i] + stiffness * po[i];
  }
}

void jacobi(const PoissonOperator& op, double mass, double stiffness, const Field& r, Field& z) {
  const StretchedGrid& g = op.grid();
  const auto& diag = op.diagonal();
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
  for (int l = 0; l < g.ny() * g.nz(); ++l) {
    const int j = l % g.ny(), k = l / g.ny();
    const double ayz = g.dy(j) * g.dz(k);
    const double* pr = &r(0, j, k);
    double* pz = &z(0, j, k);
    const std::size_t c0 = op.cell_index(0, j, k);
    for (int i = 0; i < g.nx(); ++i) pz[i] = pr[i] / (mass * g.dx(i) * ayz + stiffness * diag[c0 + i]);
  }
}

LineRange HelmholtzSolver::rhs_lines() const {
  const std::optional<LineRange> own = system_ ? system_->lines_read() : std::nullopt;
  return own ? *own : all_lines(op_.grid());
}

void HelmholtzSolver::apply(double mass, double stiffness, Field& x, Field& out) const {
  op_.apply(x, out);
  add_mass(op_, mass, stiffness, x, out);
}

namespace {

struct HelmholtzOps {
  const HelmholtzSolver& solver;
  double mass, stiffness;
  void apply(Field& x, Field& out) const { solver.apply(mass, stiffness, x, out); }
  void precondition(const Field& r, Field& z) const { jacobi(solver.op(), mass, stiffness, r, z); }
  double dot(const Field& a, const Field& b) const { return cfd::dot(a, b); }
  double norm2(const Field& a) const { return cfd::norm2(a); }
};

}  // namespace

HelmholtzStats HelmholtzSolver::solve(double mass, double stiffness, const Field& b, Field& x, double rtol,
                                      int max_iterations) {
  if (system_) return system_->solve(op_, mass, stiffness, b, x, rtol, max_iterations);
  HelmholtzOps ops{*this, mass, stiffness};
  return helmholtz_pcg(ops, b, x, rtol, max_iterations, work_);
}

}  // namespace finverse::cfd
