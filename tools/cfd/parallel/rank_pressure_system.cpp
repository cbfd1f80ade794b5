// The pressure system of a whole-flow run solved over MPI ranks; see rank_pressure_system.hpp.
#include "cfd/parallel/rank_pressure_system.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "cfd/parallel/mpi_rank_share.hpp"
#include "cfd/parallel/rank_momentum_system.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace finverse::cfd {

namespace {
// The process's time in the ranks' pressure solves (all its flows), for the run's last log line.
struct PressureTimes {
  double setup = 0, solve = 0;
  long setups = 0, solves = 0;
} g_times;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

void RankPressureSystem::setup(const PoissonOperator& op, const FaceCoefficients& beta, const PoissonSolverOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto block_beta = [&](const StretchedGrid& block_grid, const Block& b) { return block_faces(beta, block_grid, b); };
  solver_.reset();  // the old hierarchy's memory first
  solver_ = std::make_unique<DistributedPoissonSolver>(comm_, op.grid(), block_beta, op.bc(), options);
  b_ = solver_->grid().make_field(1);
  x_ = solver_->grid().make_field(1);
  g_times.setup += seconds_since(t0);
  ++g_times.setups;
}

std::optional<LineRange> RankPressureSystem::lines_read() const {
  if (!solver_) return std::nullopt;
  return solver_->grid().block();
}

PoissonSolveStats RankPressureSystem::solve_system(const PoissonOperator& op, Field& b, Field& x) {
  const auto t0 = std::chrono::steady_clock::now();
  const DistributedGrid& g = solver_->grid();
  g.own_part(b, b_);
  g.own_part(x, x_);
  const PoissonSolveStats st = solver_->solve_system(b_, x_);
  g.allgather(x_, x);
  // The serial solve's last residual filled x's periodic ghosts; the other sides' ghosts belong to
  // the caller and are left as they were.
  op.fill_ghosts(x);
  g_times.solve += seconds_since(t0);
  ++g_times.solves;
  return st;
}

FlowRanks::FlowRanks() {
  // FINVERSE_FLOW_RANKS_ON_ONE=1 takes the ranks' path on a single rank too: the scaling benchmark
  // measures what the decomposition itself costs against the threaded solver.
  const char* on_one = std::getenv("FINVERSE_FLOW_RANKS_ON_ONE");
  const bool forced = on_one != nullptr && std::string(on_one) == "1";
  if (cli::mpi_launch_size() < 2 && !forced) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (size_ != cli::mpi_launch_size()) {
    // srun without an MPI plugin starts independent singletons that would each write the files.
    const int launched = cli::mpi_launch_size();
    MPI_Finalize();
    throw Error("started as " + std::to_string(launched) + " tasks, but MPI sees " + std::to_string(size_) +
                " rank(s): the launcher did not connect them (srun needs --mpi=pmix, or the site's MPI plugin)");
  }
  MPI_Comm_dup(MPI_COMM_WORLD, &failures_);
  active_ = true;
  install_flow_pressure_system([] { return std::make_shared<RankPressureSystem>(MPI_COMM_WORLD); });
  install_flow_momentum_system([] { return std::make_shared<RankMomentumSystem>(MPI_COMM_WORLD); });
  install_rank_share(std::make_shared<MpiRankShare>(MPI_COMM_WORLD));
}

FlowRanks::~FlowRanks() {
  if (!active_) return;
  install_flow_pressure_system({});
  install_flow_momentum_system({});
  install_rank_share(nullptr);
  MPI_Comm_free(&failures_);
  MPI_Finalize();
}

bool FlowRanks::every_rank_failed(double seconds) const {
  MPI_Request barrier = MPI_REQUEST_NULL;
  MPI_Ibarrier(failures_, &barrier);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int done = 0;
  for (;;) {
    MPI_Test(&barrier, &done, MPI_STATUS_IGNORE);
    if (done || std::chrono::steady_clock::now() > deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done != 0;  // else the barrier stays posted: the job is about to be aborted
}

void FlowRanks::report_once(const char* tool, const char* what) const {
  if (rank_ == 0) {
    std::fprintf(stderr, "%s: error: %s\n", tool, what);
    std::fflush(stderr);
  }
  MPI_Barrier(failures_);
}

void FlowRanks::abort(const char* tool, const char* what, int code) const {
  if (rank_ == 0) std::fprintf(stderr, "%s: error: %s\n", tool, what);
  else std::fprintf(stderr, "%s: rank %d: error: %s\n", tool, rank_, what);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::abort();
}

int run_on_flow_ranks(const std::string& tool, const std::function<int()>& body) {
  FlowRanks ranks;
  if (!ranks.active()) return body();
  log::info("the pressure solve over " + std::to_string(ranks.size()) +
            " MPI ranks, every rank holding the whole flow (the momentum solves on the ranks too where no "
            "closed body's ghost rows join them, the closed surface's set-up in shares); rank 0 writes the files");
  try {
    const int rc = body();
    char line[200];
    std::snprintf(line, sizeof line, "pressure on %d ranks: %ld set-ups %.1f s, %ld solves %.1f s (gathers included)",
                  ranks.size(), g_times.setups, g_times.setup, g_times.solves, g_times.solve);
    log::info(line);
    return rc;
  } catch (const std::exception& e) {
    if (!ranks.every_rank_failed()) ranks.abort(tool.c_str(), e.what(), kExitError);
    // Every rank failed alike (bad input, a rank count the grid cannot take): rank 0 says it once,
    // and no rank exits before it has.
    ranks.report_once(tool.c_str(), e.what());
    throw ReportedError(e.what());
  }
}

}  // namespace finverse::cfd
