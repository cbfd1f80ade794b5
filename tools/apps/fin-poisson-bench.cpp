// fin-poisson-bench: times the pressure Poisson solver (geometric multigrid, MG-PCG by default) on
// a 3-D all-Neumann problem on a stretched grid, the shape of the fractional-step pressure solve
// (DESIGN.md section 5.1), and writes the results as a finverse/summary bench file.
//
//   fin-poisson-bench -n 64 -n 128 --json results/bench/poisson.json
//   fin-poisson-bench -n 64 --mask --smoother zebra
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "cfd/poisson_solver.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/summary.hpp"

namespace {

using namespace finverse::cfd;
using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time the multigrid pressure Poisson solver on a stretched 3-D grid"};
  finverse::cli::Standard standard(app, "fin-poisson-bench");
  std::vector<int> sizes{128};
  std::string json_path, method = "pcg", smoother = "rb", cycle = "V";
  double rtol = 1e-8, ratio = 1.1;
  int repeats = 1;
  bool mask = false;
  app.add_option("-n,--size", sizes, "cells per axis (one or more sizes, each a multiple of 8)")->capture_default_str();
  app.add_option("--rtol", rtol, "relative residual to reach")->capture_default_str();
  app.add_option("--ratio", ratio, "maximum geometric stretch ratio")->capture_default_str();
  app.add_option("--method", method, "pcg (MG-preconditioned CG) or mg (plain cycles)")
      ->check(CLI::IsMember({"pcg", "mg"}))
      ->capture_default_str();
  app.add_option("--smoother", smoother, "rb (red-black Gauss-Seidel) or zebra (alternating zebra lines)")
      ->check(CLI::IsMember({"rb", "zebra"}))
      ->capture_default_str();
  app.add_option("--cycle", cycle, "V, W or F")->check(CLI::IsMember({"V", "W", "F"}))->capture_default_str();
  app.add_flag("--mask", mask, "immerse a sphere (beta = 0 on the faces of its cells)");
  app.add_option("--repeats", repeats, "solves per size (the fastest is reported)")->capture_default_str();
  app.add_option("--json", json_path, "write a finverse/summary bench file here");
  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    const int threads = finverse::cli::threads_in_use();
    const auto t_all = clock_type::now();
    finverse::Summary summary("bench", "poisson",
                              "3-D all-Neumann pressure Poisson solve on a stretched grid to relative residual " +
                                  std::to_string(rtol) + " with geometric multigrid (" + method + ", " + smoother +
                                  " smoother, " + cycle + "-cycle)");
    bool all_converged = true;
    for (int n : sizes) {
      if (n < 8) throw finverse::Error("--size " + std::to_string(n) + ": need at least 8 cells per axis");
      // Body-fitted core of a fin-sized problem: [-0.5,1.5] x [-0.5,0.5] x [-0.25,1.25] uniform,
      // stretched to a box of a few chord lengths, all-Neumann (the fractional-step pressure).
      const StretchedGrid grid(Axis::stretched_count(-4, 8, -0.5, 1.5, n, ratio),
                               Axis::stretched_count(-4, 4, -0.5, 0.5, n, ratio),
                               Axis::stretched_count(-3, 4, -0.25, 1.25, n, ratio));
      FaceCoefficients beta(grid, 1.0);
      if (mask)
        beta.mask_cells([&](int i, int j, int k) {
          const double x = grid.xc(i) - 0.3, y = grid.yc(j), z = grid.zc(k) - 0.5;
          return x * x + y * y + z * z < 0.35 * 0.35;
        });
      PoissonSolverOptions opt;
      opt.rtol = rtol;
      opt.method = method == "pcg" ? PoissonMethod::MultigridPCG : PoissonMethod::MultigridCycles;
      opt.multigrid.smoother = smoother == "rb" ? SmootherKind::RedBlack : SmootherKind::ZebraLines;
      opt.multigrid.cycle = cycle == "V" ? CycleType::V : cycle == "W" ? CycleType::W : CycleType::F;

      // Smooth source with a nonzero mean: exercises the compatibility projection.
      Field f(grid);
      for (int k = 0; k < grid.nz(); ++k)
        for (int j = 0; j < grid.ny(); ++j)
          for (int i = 0; i < grid.nx(); ++i)
            f(i, j, k) =
                std::sin(grid.xc(i)) * std::cos(1.3 * grid.yc(j)) * std::exp(-0.1 * grid.zc(k) * grid.zc(k)) + 0.1;

      auto t0 = clock_type::now();
      PoissonSolver solver;
      solver.setup(grid, beta, BoundaryConditions::all(BcType::Neumann), opt);
      const double setup_s = seconds_since(t0);
      double solve_s = 1e300;
      PoissonSolveStats st;
      for (int r = 0; r < repeats; ++r) {
        Field p(grid);
        t0 = clock_type::now();
        st = solver.solve(f, BoundaryValues{}, p);
        solve_s = std::min(solve_s, seconds_since(t0));
      }
      all_converged = all_converged && st.converged;
      const double unknowns = static_cast<double>(grid.cells());
      const std::string tag = std::to_string(n) + "^3";
      std::printf("%s: %s, levels %s, max aspect %.1f\n", tag.c_str(), method == "pcg" ? "MG-PCG" : "MG cycles",
                  solver.multigrid().describe().c_str(), grid.max_aspect_ratio());
      std::printf(
          "  setup %.3f s, solve %.3f s, %d iterations (factor %.3f), relative residual %.2e, "
          "%.1f ns per unknown per iteration, %.1f ns per unknown, %d threads\n",
          setup_s, solve_s, st.iterations, st.convergence_factor, st.relative_residual,
          1e9 * solve_s / unknowns / std::max(1, st.iterations), 1e9 * solve_s / unknowns, threads);
      summary.info("setup_time_" + tag, setup_s, "s");
      summary.info("solve_time_" + tag, solve_s, "s");
      summary.info("iterations_" + tag, st.iterations);
      summary.info("convergence_factor_" + tag, st.convergence_factor);
      summary.info("relative_residual_" + tag, st.relative_residual);
      summary.info("solve_time_per_unknown_" + tag, solve_s / unknowns, "s");
      summary.info("max_aspect_ratio_" + tag, grid.max_aspect_ratio());
    }
    if (!json_path.empty()) {
      summary.parameters() = {{"sizes", sizes},   {"rtol", rtol},         {"max_stretch_ratio", ratio},
                              {"method", method}, {"smoother", smoother}, {"cycle", cycle},
                              {"mask", mask},     {"repeats", repeats}};
      summary.set_timing(seconds_since(t_all), threads);
      summary.write(json_path);
    }
    if (!all_converged) {
      std::fprintf(stderr, "fin-poisson-bench: a solve did not reach --rtol %g\n", rtol);
      return 1;
    }
    return 0;
  });
}
