// fin-poisson-ranks: the pressure Poisson solve on MPI ranks against the threaded solver on the
// same cores (issue 48; cfd/parallel/pressure_ranks_bench.hpp), one JSON record per launch.
// rules/bench.smk runs it on 1 and 2 ranks and tools/scripts/scaling_bench.py writes
// results/bench/scaling.json from the records.
//
//   mpirun -np 2 fin-poisson-ranks -n 64 --json ranks2.json
#include <mpi.h>

#include <fstream>
#include <string>

#include "cfd/parallel/pressure_ranks_bench.hpp"
#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  CLI::App app{"fin-poisson-ranks: the pressure solve on MPI ranks against the threaded solver"};
  finverse::cfd::PressureRanksBench bench;
  std::string json;
  app.add_option("-n", bench.n, "cells per axis")->check(CLI::Range(16, 1024))->capture_default_str();
  app.add_option("--ratio", bench.ratio, "largest stretch ratio")->check(CLI::Range(1.0, 2.0))->capture_default_str();
  app.add_option("--repeats", bench.repeats, "solves timed; the fastest counts")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_flag("!--no-mask", bench.mask, "without the immersed sphere");
  app.add_option("--json", json, "the record (written by rank 0)")->required();
  int code = 0;
  try {
    app.parse(argc, argv);
    const auto record = finverse::cfd::run_pressure_ranks_bench(MPI_COMM_WORLD, bench);
    if (rank == 0) finverse::write_text_atomic(json, record.dump(2) + "\n");
  } catch (const CLI::ParseError& e) {
    code = rank == 0 ? app.exit(e) : 2;
  } catch (const std::exception& e) {
    if (rank == 0) std::fprintf(stderr, "fin-poisson-ranks: error: %s\n", e.what());
    code = 2;
  }
  MPI_Finalize();
  return code;
}
