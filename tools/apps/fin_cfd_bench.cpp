// fin-cfd-bench: writes results/bench/cfd.json, the flow solver's benchmark file (issue 4):
//   - the pressure Poisson part, taken over from fin-poisson-bench's summary (--poisson): finverse
//     MG-PCG against hypre PFMG / BoomerAMG on the same stretched all-Neumann matrix, with the
//     graded time ratio;
//   - the cost per cell per time step of the whole fractional step on the 3-D Taylor-Green vortex
//     (cfd/flow_cost_bench.hpp) at several grid sizes, graded for flatness;
//   - a place for the DFG 2D-2 wall-time comparison against OpenFOAM, marked "not measured" until
//     that benchmark exists.
//
//   fin-cfd-bench -n 64 -n 96 -n 128 --poisson results/bench/poisson.json --json results/bench/cfd.json
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cfd/flow_cost_bench.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/summary.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Cost per cell per time step of the flow solver, merged with the Poisson benchmark"};
  finverse::cli::Standard standard(app, "fin-cfd-bench");
  std::vector<int> sizes{64, 96, 128};
  std::string json_path, poisson_path;
  int warmup = 2, steps = 5;
  double stretch = 0.3, flat_goal = 1.25;
  app.add_option("-n,--size", sizes, "cells per axis (multiples of 4)")->capture_default_str();
  app.add_option("--warmup", warmup, "untimed steps before timing")->capture_default_str();
  app.add_option("--steps", steps, "timed steps per size")->capture_default_str();
  app.add_option("--stretch", stretch, "grid non-uniformity s of x = xi + s sin(xi), 0 <= s < 1")
      ->capture_default_str();
  app.add_option("--flat-goal", flat_goal, "graded: largest / smallest cost per cell per step <= this")
      ->capture_default_str();
  app.add_option("--poisson", poisson_path, "fin-poisson-bench summary (with --peer) to include");
  app.add_option("--json", json_path, "write the finverse/summary bench file here");

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    const auto t_all = std::chrono::steady_clock::now();
    finverse::Summary summary("bench", "cfd",
                              "flow solver: pressure Poisson solve vs hypre, cost per cell per time step, "
                              "DFG 2D-2 vs OpenFOAM");
    nlohmann::json poisson_parameters = nullptr;
    if (!poisson_path.empty()) {
      finverse::Summary poisson("bench", "poisson", "");
      try {
        poisson = finverse::Summary::read(poisson_path);
      } catch (const std::exception& e) {
        throw finverse::Error("--poisson " + poisson_path + ": not a readable summary file: " + e.what());
      }
      for (const finverse::Metric& m : poisson.metrics()) {
        const std::string name = "poisson_" + m.name;
        if (m.kind == "max" && m.tolerance)
          summary.at_most(name, m.value, *m.tolerance, m.source, m.units);
        else
          summary.info(name, m.value, m.units);
      }
      poisson_parameters = poisson.parameters();
    }
    std::vector<double> cost;
    for (int n : sizes) {
      if (n < 8 || n % 4 != 0) throw finverse::Error("--size " + std::to_string(n) + ": need a multiple of 4, >= 8");
      const auto r = finverse::cfd::run_flow_cost_bench(n, warmup, steps, stretch);
      const std::string tag = std::to_string(n) + "^3";
      std::printf(
          "Taylor-Green %s: setup %.2f s, %.3f s per step, %.1f ns per cell per step, Poisson %.1f and Helmholtz "
          "%.1f iterations per step, max div %.1e\n",
          tag.c_str(), r.setup_s, r.seconds_per_step, r.ns_per_cell_step, r.mean_poisson_iterations,
          r.mean_helmholtz_iterations, r.max_divergence);
      std::fflush(stdout);
      summary.info("step_time_" + tag, r.seconds_per_step, "s");
      summary.info("cost_per_cell_step_" + tag, 1e-9 * r.ns_per_cell_step, "s");
      summary.info("poisson_iterations_per_step_" + tag, r.mean_poisson_iterations);
      summary.info("helmholtz_iterations_per_step_" + tag, r.mean_helmholtz_iterations);
      cost.push_back(r.ns_per_cell_step);
    }
    if (cost.size() >= 2) {
      const auto [lo, hi] = std::minmax_element(cost.begin(), cost.end());
      summary.at_most("cost_per_cell_step_spread", *hi / *lo, flat_goal,
                      "issue 4: cost per cell per time step should stay flat over grid sizes");
    }
    summary.parameters() = {
        {"sizes", sizes},
        {"warmup_steps", warmup},
        {"timed_steps", steps},
        {"stretch", stretch},
        {"case", "3-D Taylor-Green vortex, Re 1600, periodic [0, 2 pi]^3, CFL 0.5"},
        {"poisson", poisson_parameters},
        {"dfg_2d2_vs_openfoam",
         {{"status", "not measured"},
          {"goal",
           "finverse wall time <= 0.5 x OpenFOAM (pimpleFoam/icoFoam) for DFG 2D-2 inside 1% of the bounds, "
           "same 2 cores"}}}};
    if (!json_path.empty()) {
      summary.set_timing(std::chrono::duration<double>(std::chrono::steady_clock::now() - t_all).count(),
                         finverse::cli::threads_in_use());
      summary.write(json_path);
    }
    return summary.pass() ? 0 : 1;
  });
}
