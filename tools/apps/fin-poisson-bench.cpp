// fin-poisson-bench: times the pressure Poisson solver (geometric multigrid, MG-PCG by default) on
// the benchmark problem of cfd/poisson_bench_problem.hpp (3-D, stretched, all-Neumann: the shape
// of the fractional-step pressure solve, DESIGN.md section 5.1) and writes a finverse/summary
// bench file. With --peer, it also reads the result of fin-poisson-hypre on the same problem and
// grades the time ratio against hypre's best solver (goal <= 0.5).
//
//   fin-poisson-bench -n 64 -n 128 --json results/bench/poisson.json
//   mpirun -np 2 fin-poisson-hypre -n 128 --json hypre.json && fin-poisson-bench -n 128 --peer hypre.json
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "cfd/validation/poisson_bench_problem.hpp"
#include "cfd/poisson/poisson_solver.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/summary.hpp"

namespace {

using namespace finverse::cfd;
using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }

// Fastest peer time (setup + solve) for an n^3 grid in a fin-poisson-hypre JSON, and its solver.
std::pair<double, std::string> best_peer_time(const nlohmann::json& peer, int n) {
  double best = std::numeric_limits<double>::infinity();
  std::string name;
  for (const auto& r : peer.at("runs"))
    if (r.at("n").get<int>() == n && r.at("converged").get<bool>()) {
      const double t = r.at("setup_s").get<double>() + r.at("solve_s").get<double>();
      if (t < best) best = t, name = r.at("solver").get<std::string>();
    }
  return {best, name};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time the multigrid pressure Poisson solver on a stretched 3-D grid"};
  finverse::cli::Standard standard(app, "fin-poisson-bench");
  std::vector<int> sizes{128};
  std::string json_path, peer_path, method = "pcg", smoother = "rb", cycle = "V";
  double rtol = 1e-8, ratio = 1.1, coarsening_ratio = MultigridOptions{}.coarsening_ratio, relaxation = 0;
  int repeats = 1, pre = MultigridOptions{}.pre_sweeps, post = MultigridOptions{}.post_sweeps;
  bool mask = false;
  app.add_option("-n,--size", sizes, "cells per axis (one or more sizes, each a multiple of 8)")->capture_default_str();
  app.add_option("--rtol", rtol, "relative residual to reach")->capture_default_str();
  app.add_option("--ratio", ratio, "maximum geometric stretch ratio (1: uniform grid over the same box)")
      ->capture_default_str();
  app.add_option("--method", method, "pcg (MG-preconditioned CG) or mg (plain cycles)")
      ->check(CLI::IsMember({"pcg", "mg"}))
      ->capture_default_str();
  app.add_option("--smoother", smoother, "rb (red-black Gauss-Seidel) or zebra (alternating zebra lines)")
      ->check(CLI::IsMember({"rb", "zebra"}))
      ->capture_default_str();
  app.add_option("--cycle", cycle, "V, W or F")->check(CLI::IsMember({"V", "W", "F"}))->capture_default_str();
  app.add_option("--coarsening-ratio", coarsening_ratio,
                 "merge cells no wider than this times the narrowest (<= 0: halve every axis)")
      ->capture_default_str();
  app.add_option("--relaxation", relaxation, "red-black over-relaxation (0: the default per dimension)")
      ->capture_default_str();
  app.add_option("--pre", pre, "pre-smoothing sweeps")->capture_default_str();
  app.add_option("--post", post, "post-smoothing sweeps")->capture_default_str();
  app.add_flag("--mask", mask, "immerse a sphere (beta = 0 on the faces of its cells)");
  app.add_option("--repeats", repeats, "solves per size (the fastest is reported)")->capture_default_str();
  app.add_option("--json", json_path, "write a finverse/summary bench file here");
  app.add_option("--peer", peer_path, "fin-poisson-hypre JSON of the same problem: grade the time ratio");

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    const int threads = finverse::cli::threads_in_use();
    const auto t_all = clock_type::now();
    finverse::Summary summary("bench", "poisson",
                              "3-D all-Neumann pressure Poisson solve on a stretched grid to relative residual " +
                                  std::to_string(rtol) + " with geometric multigrid (" + method + ", " + smoother +
                                  " smoother, " + cycle + "-cycle)");
    nlohmann::json peer;
    if (!peer_path.empty()) {
      std::ifstream in(peer_path);
      if (!in) throw finverse::Error("--peer " + peer_path + ": cannot open");
      try {
        peer = nlohmann::json::parse(in);
      } catch (const nlohmann::json::exception& e) {
        throw finverse::Error("--peer " + peer_path + ": malformed JSON: " + e.what());
      }
    }
    bool all_converged = true;
    for (int n : sizes) {
      if (n < 8) throw finverse::Error("--size " + std::to_string(n) + ": need at least 8 cells per axis");
      const auto problem = make_poisson_bench_problem(n, ratio, mask);
      const auto& grid = problem.grid;
      PoissonSolverOptions opt;
      opt.rtol = rtol;
      opt.method = method == "pcg" ? PoissonMethod::MultigridPCG : PoissonMethod::MultigridCycles;
      opt.multigrid.smoother = smoother == "rb" ? SmootherKind::RedBlack : SmootherKind::ZebraLines;
      opt.multigrid.cycle = cycle == "V" ? CycleType::V : cycle == "W" ? CycleType::W : CycleType::F;
      opt.multigrid.coarsening_ratio = coarsening_ratio;
      opt.multigrid.relaxation = relaxation;
      opt.multigrid.pre_sweeps = pre;
      opt.multigrid.post_sweeps = post;

      auto t0 = clock_type::now();
      PoissonSolver solver;
      solver.setup(grid, problem.beta, problem.bc, opt);
      const double setup_s = seconds_since(t0);
      double solve_s = 1e300;
      PoissonSolveStats st;
      for (int r = 0; r < repeats; ++r) {
        Field p(grid);
        t0 = clock_type::now();
        st = solver.solve(problem.source, BoundaryValues{}, p);
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
      if (!peer.is_null()) {
        const auto [peer_s, peer_name] = best_peer_time(peer, n);
        if (!std::isfinite(peer_s)) throw finverse::Error("--peer " + peer_path + ": no converged run for n = " + std::to_string(n));
        summary.info("hypre_best_time_" + tag, peer_s, "s");
        summary.at_most("time_ratio_vs_hypre_" + tag, (setup_s + solve_s) / peer_s, 0.5,
                        "goal of issue 4: finverse (setup+solve) <= 0.5 x hypre's best (" + peer_name + ")");
        std::printf("  hypre best: %s %.3f s; ratio %.2f\n", peer_name.c_str(), peer_s, (setup_s + solve_s) / peer_s);
      }
    }
    if (!json_path.empty()) {
      summary.parameters() = {{"sizes", sizes}, {"rtol", rtol}, {"max_stretch_ratio", ratio}, {"method", method},
                              {"smoother", smoother}, {"cycle", cycle}, {"mask", mask}, {"repeats", repeats},
                              {"coarsening_ratio", coarsening_ratio}, {"relaxation", relaxation}, {"pre_sweeps", pre},
                              {"post_sweeps", post},
                              {"peer", peer.is_null() ? nlohmann::json(nullptr) : peer}};
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
