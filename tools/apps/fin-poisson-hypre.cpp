// fin-poisson-hypre: the peer of fin-poisson-bench. Solves the same benchmark problem with hypre's
// PFMG and BoomerAMG, each preconditioning CG (cfd/validation/hypre_poisson.hpp), and writes the
// timings as JSON for fin-poisson-bench --peer. Built only where Debian's libhypre-dev is installed
// (tools/scripts/install-deps.sh --peers); hypre is MPI-parallel, so run it on the same cores as
// finverse: mpirun -np 2 fin-poisson-hypre -n 128 --json hypre.json
#include <HYPRE_utilities.h>
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cfd/validation/hypre_poisson.hpp"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  CLI::App app{"fin-poisson-hypre: hypre PFMG and BoomerAMG on fin-poisson-bench's problem"};
  std::vector<int> sizes{128};
  double rtol = 1e-8, ratio = 1.1;
  bool mask = false;
  std::string json_path;
  app.add_option("-n,--size", sizes, "cells per axis")->capture_default_str();
  app.add_option("--rtol", rtol, "relative residual (two-norm)")->capture_default_str();
  app.add_option("--ratio", ratio, "maximum geometric stretch ratio")->capture_default_str();
  app.add_flag("--mask", mask, "immerse a sphere");
  app.add_option("--json", json_path, "write the timings here (rank 0)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    MPI_Finalize();
    return rc == 0 ? 0 : 2;
  }
  HYPRE_Init();
  nlohmann::json out = {
      {"peer", "hypre (Debian libhypre-dev)"}, {"ranks", size}, {"rtol", rtol}, {"runs", nlohmann::json::array()}};
  for (int n : sizes) {
    for (const auto& r : finverse::cfd::validation::solve_poisson_bench_with_hypre(n, ratio, mask, rtol, rank, size)) {
      if (rank == 0)
        std::printf("%d^3 %-14s setup %.3f s  solve %.3f s  %d iterations  relative residual %.2e\n", n,
                    r.solver.c_str(), r.setup_s, r.solve_s, r.iterations, r.relative_residual);
      out["runs"].push_back({{"n", n},
                             {"solver", r.solver},
                             {"setup_s", r.setup_s},
                             {"solve_s", r.solve_s},
                             {"iterations", r.iterations},
                             {"relative_residual", r.relative_residual},
                             {"converged", r.converged}});
    }
  }
  if (rank == 0 && !json_path.empty()) {
    const std::string tmp = json_path + ".tmp";
    std::ofstream(tmp) << out.dump(2) << "\n";
    std::rename(tmp.c_str(), json_path.c_str());
  }
  HYPRE_Finalize();
  MPI_Finalize();
  return 0;
}
