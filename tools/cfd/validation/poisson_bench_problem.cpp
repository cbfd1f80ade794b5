// The pressure-Poisson benchmark problem (see poisson_bench_problem.hpp).
#include "cfd/validation/poisson_bench_problem.hpp"

#include <cmath>

namespace finverse::cfd {

PoissonBenchProblem make_poisson_bench_problem(int n, double ratio, bool mask) {
  const auto axis = [&](double lo, double hi, double ulo, double uhi) {
    return ratio == 1.0 ? Axis::uniform(lo, hi, n) : Axis::stretched_count(lo, hi, ulo, uhi, n, ratio);
  };
  const StretchedGrid grid(axis(-4, 8, -0.5, 1.5), axis(-4, 4, -0.5, 0.5), axis(-3, 4, -0.25, 1.25));
  FaceCoefficients beta(grid, 1.0);
  if (mask)
    beta.mask_cells([&](int i, int j, int k) {
      const double x = grid.xc(i) - 0.3, y = grid.yc(j), z = grid.zc(k) - 0.5;
      return x * x + y * y + z * z < 0.35 * 0.35;
    });
  Field f(grid);
  for (int k = 0; k < grid.nz(); ++k)
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i)
        f(i, j, k) = std::sin(grid.xc(i)) * std::cos(1.3 * grid.yc(j)) * std::exp(-0.1 * grid.zc(k) * grid.zc(k)) + 0.1;
  return {grid, beta, BoundaryConditions::all(BcType::Neumann), f};
}

}  // namespace finverse::cfd
