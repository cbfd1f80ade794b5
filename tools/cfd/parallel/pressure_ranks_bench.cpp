// The pressure solve on MPI ranks against the threaded solver; see pressure_ranks_bench.hpp.
#include "cfd/parallel/pressure_ranks_bench.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "cfd/parallel/distributed_poisson_solver.hpp"
#include "cfd/validation/poisson_bench_problem.hpp"

namespace finverse::cfd {
namespace {

using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }

// A barrier whose waiting ranks sleep: Open MPI's own barrier polls, and a polling rank takes the
// core that the threaded run on rank 0 is being timed on.
void sleeping_barrier(MPI_Comm comm) {
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    usleep(500);
  }
}

}  // namespace

nlohmann::json run_pressure_ranks_bench(MPI_Comm comm, const PressureRanksBench& bench) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const PoissonBenchProblem problem = make_poisson_bench_problem(bench.n, bench.ratio, bench.mask);
  const StretchedGrid& whole = problem.grid;
  PoissonSolverOptions options;
  nlohmann::json out;
  // The threaded solver on rank 0 with one thread per rank of the job; the others sleep.
  Field serial_x(whole, 1);
  if (rank == 0) {
    omp_set_num_threads(ranks);
    double setup = std::numeric_limits<double>::infinity(), solve = setup;
    PoissonSolveStats st;
    for (int r = 0; r < bench.repeats; ++r) {
      auto t0 = clock_type::now();
      PoissonSolver solver;
      solver.setup(whole, problem.beta, problem.bc, options);
      setup = std::min(setup, since(t0));
      Field b(whole, 1);
      solver.op().assemble_rhs(problem.source, BoundaryValues{}, b);
      serial_x.fill(0.0);
      t0 = clock_type::now();
      st = solver.solve_system(b, serial_x);
      solve = std::min(solve, since(t0));
    }
    out["threaded"] = {{"threads", ranks}, {"setup_s", setup}, {"solve_s", solve}, {"iterations", st.iterations},
                       {"converged", st.converged}};
    omp_set_num_threads(1);
  }
  sleeping_barrier(comm);
  omp_set_num_threads(1);
  // The ranks, one thread each.
  const auto block_beta = [&](const StretchedGrid& block_grid, const Block& blk) {
    return block_faces(problem.beta, block_grid, blk);
  };
  double setup = std::numeric_limits<double>::infinity(), solve = setup;
  PoissonSolveStats st;
  std::size_t halo = 0;
  long exchanges = 0, reductions = 0;
  Field gathered(whole.nx(), whole.ny(), whole.nz(), whole.dim(), 0);
  std::unique_ptr<DistributedPoissonSolver> keep;
  for (int r = 0; r < bench.repeats; ++r) {
    MPI_Barrier(comm);
    auto t0 = clock_type::now();
    auto solver = std::make_unique<DistributedPoissonSolver>(comm, whole, block_beta, problem.bc, options);
    MPI_Barrier(comm);
    setup = std::min(setup, since(t0));
    // The right-hand side as the threaded run assembles it (-f V on active cells), on the block.
    const DistributedGrid& g = solver->grid();
    const Block& blk = g.block();
    const StretchedGrid block_grid = whole.block(blk.j0, blk.j1, blk.k0, blk.k1);
    Field b = g.make_field(1), x = g.make_field(1);
    for (int k = 0; k < b.nz(); ++k)
      for (int j = 0; j < b.ny(); ++j)
        for (int i = 0; i < b.nx(); ++i)
          b(i, j, k) = solver->op().block_operator().active(i, j, k)
                           ? -problem.source(i, j + blk.j0, k + blk.k0) * block_grid.volume(i, j, k)
                           : 0.0;
    const std::size_t halo0 = g.halo_doubles_total();
    const long ex0 = g.exchanges(), red0 = g.reductions();
    MPI_Barrier(comm);
    t0 = clock_type::now();
    st = solver->solve_system(b, x);
    MPI_Barrier(comm);
    solve = std::min(solve, since(t0));
    halo = g.halo_doubles_total() - halo0, exchanges = g.exchanges() - ex0, reductions = g.reductions() - red0;
    g.gather(x, gathered);
    keep = std::move(solver);
  }
  unsigned long long most_halo = halo;
  MPI_Allreduce(MPI_IN_PLACE, &most_halo, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, comm);
  if (rank != 0) return {};
  double diff = 0, scale = 0;
  for (int k = 0; k < whole.nz(); ++k)
    for (int j = 0; j < whole.ny(); ++j)
      for (int i = 0; i < whole.nx(); ++i)
        diff = std::max(diff, std::abs(gathered(i, j, k) - serial_x(i, j, k))), scale = std::max(scale, std::abs(serial_x(i, j, k)));
  const auto& d = keep->grid().decomposition();
  const auto& mg = keep->multigrid();
  const int D = mg.gathered_level();
  out["ranks"] = ranks;
  out["n"] = bench.n, out["ratio"] = bench.ratio, out["mask"] = bench.mask;
  out["cells"] = whole.cells();
  out["lines"] = static_cast<long>(whole.ny()) * whole.nz();
  out["split"] = {{"py", d.py()}, {"pz", d.pz()}};
  out["ranks_run"] = {{"setup_s", setup},
                      {"solve_s", solve},
                      {"iterations", st.iterations},
                      {"converged", st.converged},
                      {"levels", mg.levels()},
                      {"gathered_level", D},
                      {"halo_doubles_per_solve_max_rank", most_halo},
                      {"exchanges_per_solve", exchanges},
                      {"reductions_per_solve", reductions}};
  out["solution_max_difference_relative"] = scale > 0 ? diff / scale : diff;
  return out;
}

}  // namespace finverse::cfd
