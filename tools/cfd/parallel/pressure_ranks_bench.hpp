// The pressure solve on MPI ranks against the threaded solver on the same cores (issue 48's
// scaling benchmark, the part that is distributed today; docs/studies/flow_mpi.md): the
// benchmark problem of cfd/validation/poisson_bench_problem.hpp (3-D, stretched, all-Neumann,
// optionally a masked sphere) solved by PoissonSolver with as many threads as the job has ranks,
// then by DistributedPoissonSolver on the ranks with one thread each; times, iterations, the
// halo and reduction traffic per rank, the agreement of the two solutions.
#pragma once

#include <mpi.h>

#include <nlohmann/json.hpp>

namespace finverse::cfd {

struct PressureRanksBench {
  int n = 64;          // cells per axis
  double ratio = 1.1;  // largest stretch ratio
  bool mask = true;    // the immersed sphere
  int repeats = 3;     // the fastest of these solves counts
};

// Collective. Rank 0 returns the record; the other ranks an empty object.
nlohmann::json run_pressure_ranks_bench(MPI_Comm comm, const PressureRanksBench& bench);

}  // namespace finverse::cfd
