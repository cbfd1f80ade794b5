// fin-cfd-bench: writes results/bench/cfd.json, the flow solver's benchmark file (issue 4;
// rules/bench.smk): the pressure Poisson part taken over from fin-poisson-bench's summary
// (cfd/validation/poisson_bench_metrics.hpp), the cost per cell per time step over grid sizes
// (cfd/validation/flow_cost_flatness.hpp), and DFG 2D-2 (graded) and 2D-3 (reported) wall time
// against OpenFOAM at equal accuracy (cfd/validation/dfg_peer_comparison.hpp).
//
//   fin-cfd-bench -n 64 -n 96 -n 128 --poisson results/bench/poisson.json --json results/bench/cfd.json
//   fin-cfd-bench -n 16 --dfg N32/dfg_2d2/summary.json --dfg N48/dfg_2d2/summary.json
//                 --openfoam results/bench/dfg2d2/openfoam.json
//                 --openfoam results/bench/dfg2d2/openfoam_courant0.25.json
//                 --dfg2d3 N/dfg_2d3/summary.json --openfoam2d3 results/bench/dfg2d3/openfoam.json
//                 --json results/bench/cfd_dfg_studies.json
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cfd/validation/dfg_peer_comparison.hpp"
#include "cfd/validation/flow_cost_flatness.hpp"
#include "cfd/validation/poisson_bench_metrics.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/summary.hpp"

namespace v = finverse::cfd::validation;

int main(int argc, char** argv) {
  CLI::App app{"Cost per cell per time step of the flow solver, merged with the Poisson benchmark"};
  finverse::cli::Standard standard(app, "fin-cfd-bench");
  v::FlowCostSettings cost;
  std::string json_path, poisson_path;
  app.add_option("-n,--size", cost.sizes, "cells per axis (multiples of 4)")->capture_default_str();
  app.add_option("--warmup", cost.warmup, "untimed steps before timing")->capture_default_str();
  app.add_option("--steps", cost.steps, "timed steps per size")->capture_default_str();
  app.add_option("--stretch", cost.stretch, "grid non-uniformity s of x = xi + s sin(xi), 0 <= s < 1")
      ->capture_default_str();
  app.add_option("--flat-goal", cost.flat_goal, "graded: largest / smallest cost per cell per step <= this")
      ->capture_default_str();
  app.add_option("--poisson", poisson_path, "fin-poisson-bench summary (with --peer) to include");
  std::vector<std::string> dfg_paths, dfg3_paths;
  std::vector<std::string> openfoam_paths, openfoam3_paths;
  app.add_option("--dfg", dfg_paths, "fin-cfd dfg_2d2 summary (full variant) to time against OpenFOAM; repeatable")
      ->check(CLI::ExistingFile);
  app.add_option("--openfoam", openfoam_paths,
                 "tools/scripts/openfoam_dfg.py output for the same case; repeatable (e.g. a second time step)")
      ->check(CLI::ExistingFile);
  app.add_option("--dfg2d3", dfg3_paths, "fin-cfd dfg_2d3 summary (full variant) to time against OpenFOAM; repeatable")
      ->check(CLI::ExistingFile);
  app.add_option("--openfoam2d3", openfoam3_paths, "tools/scripts/openfoam_dfg.py --benchmark 2d3 output; repeatable")
      ->check(CLI::ExistingFile);
  app.add_option("--json", json_path, "write the finverse/summary bench file here");

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    const auto t_all = std::chrono::steady_clock::now();
    finverse::Summary summary("bench", "cfd",
                              "flow solver: pressure Poisson solve vs hypre, cost per cell per time step, "
                              "DFG 2D-2 (and 2D-3) vs OpenFOAM");
    // Read first: bad input fails before the timing runs.
    const v::DfgComparison dfg = v::compare_dfg_with_openfoam(summary, dfg_paths, openfoam_paths, v::dfg_2d2_case());
    if (!dfg.line.empty()) std::printf("%s\n", dfg.line.c_str());
    const v::DfgComparison dfg3 = v::compare_dfg_with_openfoam(summary, dfg3_paths, openfoam3_paths, v::dfg_2d3_case());
    if (!dfg3.line.empty()) std::printf("%s\n", dfg3.line.c_str());
    nlohmann::json poisson_parameters = nullptr;
    if (!poisson_path.empty()) {
      finverse::Summary poisson("bench", "poisson", "");
      try {
        poisson = finverse::Summary::read(poisson_path);
      } catch (const std::exception& e) {
        throw finverse::Error("--poisson " + poisson_path + ": not a readable summary file: " + e.what());
      }
      poisson_parameters = v::add_poisson_bench_metrics(summary, poisson);
    }
    v::run_flow_cost_sizes(summary, cost, [](const finverse::cfd::FlowCostResult& r) {
      std::printf("%s\n", v::flow_cost_line(r).c_str());
      std::fflush(stdout);
    });
    summary.parameters() = v::flow_cost_parameters(cost);
    summary.parameters()["poisson"] = poisson_parameters;
    summary.parameters()["dfg_2d2_vs_openfoam"] = dfg.parameters;
    summary.parameters()["dfg_2d3_vs_openfoam"] = dfg3.parameters;
    if (!json_path.empty()) {
      summary.set_timing(std::chrono::duration<double>(std::chrono::steady_clock::now() - t_all).count(),
                         finverse::cli::threads_in_use());
      summary.write(json_path);
    }
    return summary.pass() ? 0 : 1;
  });
}
