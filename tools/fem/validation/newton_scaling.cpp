// Newton-iteration cost against problem size (see newton_scaling.hpp).
#include "fem/validation/newton_scaling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "fem/static_solver.hpp"

namespace finverse::fem::validation {

std::vector<NewtonScalingPoint> newton_scaling(const HybridPlateCase& c, const std::vector<int>& sizes,
                                               SolverBackend backend) {
  std::vector<NewtonScalingPoint> out;
  for (int n : sizes) {
    // nz a multiple of 2 keeps the beams (z = -0.5, 0, 0.5 in the shipped case) on grid lines.
    HybridPlateModel hp = build_hybrid_plate(c, n, n, HybridPlateLoad::pressure);
    StaticOptions so;
    so.backend = backend;
    so.steps = 1;
    StaticSolver solver(hp.model, so);
    // A tenth of the pressure: a mildly nonlinear step with a few iterations.
    NodalState warm = hp.model.reference_state();
    solver.solve(warm, 0.0, 0.1);
    NodalState s = hp.model.reference_state();
    const auto t0 = std::chrono::steady_clock::now();
    const StaticResult r = solver.solve(s, 0.0, 0.1);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.push_back({n, solver.dofs().free(), r.total_iterations, sec / std::max(1, r.total_iterations)});
  }
  return out;
}

double growth_exponent(const std::vector<NewtonScalingPoint>& p) {
  const double m = static_cast<double>(p.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& q : p) {
    const double x = std::log(static_cast<double>(q.free_dofs)), y = std::log(q.seconds_per_iteration);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

}  // namespace finverse::fem::validation
