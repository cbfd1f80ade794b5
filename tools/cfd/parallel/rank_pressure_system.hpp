// fin-cfd on MPI ranks, first step (issue 48; docs/studies/flow_mpi.md, "fin-cfd on ranks"):
// every rank holds the whole grid and runs the flow solver's explicit parts, the immersed surface
// and the loads itself (the same code on the same data, so the same bits on every rank), while
// the pressure system, the step's costliest part, is solved over the ranks. Each rank takes its
// block of b and x, DistributedPoissonSolver solves (the serial MG-PCG's iterates bit for bit when
// the pressure has a Dirichlet face, as every fin run's outlet gives it), and the solution is
// gathered onto every rank. So loads.h5 does not depend on the rank count, and rank 0 writes it.
// Memory per rank is the whole flow's; the blocks-only flow (explicit stencils, the surface
// across ranks) replaces the whole fields one part at a time behind this same interface.
#pragma once

#include <mpi.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "cfd/parallel/distributed_poisson_solver.hpp"

namespace finverse::cfd {

class RankPressureSystem : public PoissonSystemSolver {
 public:
  explicit RankPressureSystem(MPI_Comm comm) : comm_(comm) {}

  // Collective: the ranks' solver for the whole operator `op` (each rank's block of beta).
  void setup(const PoissonOperator& op, const FaceCoefficients& beta, const PoissonSolverOptions& options) override;
  // Collective: b and x whole on every rank, x the solution on every rank on return.
  PoissonSolveStats solve_system(const PoissonOperator& op, Field& b, Field& x) override;

  const DistributedPoissonSolver& solver() const { return *solver_; }

  // This rank's block: the lines of b that solve reads.
  std::optional<LineRange> lines_read() const override;

 private:
  MPI_Comm comm_;
  std::unique_ptr<DistributedPoissonSolver> solver_;
  Field b_, x_;  // this rank's block
};

// MPI for a run of whole-flow ranks: initialised when an MPI launcher started the process on more
// than one rank, with RankPressureSystem and RankMomentumSystem installed for every flow solver the
// process sets up and the rank share (mpi_rank_share.hpp) for the loops built in shares, the closed
// surface's set-up; uninstalled and finalised at the end. Nothing at all without a launcher, unless
// FINVERSE_FLOW_RANKS_ON_ONE=1 asks for the ranks' path on one rank (the scaling benchmark).
class FlowRanks {
 public:
  FlowRanks();
  ~FlowRanks();
  FlowRanks(const FlowRanks&) = delete;
  FlowRanks& operator=(const FlowRanks&) = delete;

  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  // After a failure on this rank: whether every rank failed too within `seconds` (a failure every
  // rank meets, as bad input or a rank count the grid cannot take: rank 0 alone then says it and
  // the job ends normally). Meets the others on a communicator of its own.
  bool every_rank_failed(double seconds = 3) const;
  // After every_rank_failed(): rank 0 says `what` in one line, and every rank waits until it has.
  void report_once(const char* tool, const char* what) const;
  // A failure of this rank alone: says it (rank 0 plainly, the others with their rank) and ends
  // the whole job with `code`; the other ranks may wait in a collective that would never complete.
  [[noreturn]] void abort(const char* tool, const char* what, int code) const;

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
  MPI_Comm failures_ = MPI_COMM_NULL;
};

// body() as a flow run on the ranks a launcher started (FlowRanks), or plainly without one. A
// failure on any rank ends the whole job: every rank's together with rank 0's one line, a lone
// rank's by aborting the job.
int run_on_flow_ranks(const std::string& tool, const std::function<int()>& body);

}  // namespace finverse::cfd
