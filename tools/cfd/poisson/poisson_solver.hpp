// Pressure Poisson solver: div(beta grad p) = f on a stretched grid with per-side boundary
// conditions and an optional immersed-boundary face mask, solved by geometric multigrid, either as
// a stand-alone iteration of cycles or as the preconditioner of conjugate gradients (MG-PCG).
//
// MG-PCG is the default: it is as fast as plain cycles on smooth problems and markedly more robust
// where the rediscretised coarse operators match the fine one poorly (immersed-boundary masks,
// strong stretching), because CG removes the few slowly converging error components that the
// cycle leaves behind.
//
// Null space: on every singular component (no Dirichlet face) the right-hand side is made
// compatible (a uniform shift of f, which is what discretisation error in a boundary flux amounts
// to) and the solution's volume-weighted mean is set to zero.
//
// Stopping: ||b - A x||_2 <= rtol ||b||_2 for the volume-integrated system (after the
// compatibility projection), or max_iterations.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/poisson/multigrid.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

enum class PoissonMethod { MultigridCycles, MultigridPCG };

struct PoissonSolverOptions {
  PoissonMethod method = PoissonMethod::MultigridPCG;
  MultigridOptions multigrid;
  double rtol = 1e-8;
  int max_iterations = 200;
};

struct PoissonSolveStats {
  int iterations = 0;
  bool converged = false;
  double initial_residual = 0;   // ||b - A x0||
  double rhs_norm = 0;           // ||b||
  double relative_residual = 0;  // ||b - A x|| / ||b||
  // Mean reduction of the residual per iteration, (r_n / r_0)^(1/n).
  double convergence_factor = 0;
  std::vector<double> history;  // ||r|| after each iteration, history[0] = initial
};

// Work vectors of the iterations (mg_pcg.hpp): residual, preconditioned residual, A d, direction.
struct SolveWork {
  Field r, z, q, d;
};

// A solver of the assembled system that takes the multigrid's place: the MPI ranks' one
// (cfd/parallel/rank_pressure_system.hpp). It sees every operator PoissonSolver builds, and
// solves with it as solve_poisson_system (mg_pcg.hpp) does: x as that leaves it, ghosts included;
// b is scratch afterwards.
class PoissonSystemSolver {
 public:
  virtual ~PoissonSystemSolver() = default;
  virtual void setup(const PoissonOperator& op, const FaceCoefficients& beta, const PoissonSolverOptions& options) = 0;
  virtual PoissonSolveStats solve_system(const PoissonOperator& op, Field& b, Field& x) = 0;
  // The lines of b that solve_system reads once set up (an MPI rank's block); empty: all of them.
  virtual std::optional<LineRange> lines_read() const { return std::nullopt; }
};

// The process's flow solvers (FlowSolver::setup) take their pressure system solver from this
// factory once one is installed: fin-cfd and fin-fsi under an MPI launcher install the ranks'
// one, so every flow of the run (a validation case's grids, the FSI's flow) solves its pressure on
// the ranks. Empty (the default): the threaded multigrid.
using PoissonSystemFactory = std::function<std::shared_ptr<PoissonSystemSolver>()>;
void install_flow_pressure_system(PoissonSystemFactory factory);
std::shared_ptr<PoissonSystemSolver> make_flow_pressure_system();

// Wall time a PoissonSolver spent in its set-ups and solves (the scaling benchmark splits a flow
// step into the pressure and the rest with it: docs/studies/flow_mpi.md).
struct PoissonTimes {
  long setups = 0, solves = 0;
  double setup_seconds = 0, solve_seconds = 0;
};

class PoissonSolver {
 public:
  // Solve the systems with `system` instead of the multigrid (null: the multigrid); takes effect
  // at the next setup().
  void set_system_solver(std::shared_ptr<PoissonSystemSolver> system) { system_ = std::move(system); }

  // Builds the operator and the multigrid hierarchy.
  void setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc,
             const PoissonSolverOptions& options = {});

  // Solves div(beta grad p) = f with the given boundary values; p holds the initial guess on
  // entry (the previous time step's pressure is a good one) and the solution on exit.
  PoissonSolveStats solve(const Field& f, const BoundaryValues& values, Field& p);

  // Solves the volume-integrated system A x = b directly (b is made compatible in place).
  PoissonSolveStats solve_system(Field& b, Field& x);
  // The lines of f (solve) and b (solve_system) that the solve reads: all of them, or an MPI rank's
  // block when the ranks solve the system (its caller may leave the rest of f unset).
  LineRange rhs_lines() const;

  const PoissonOperator& op() const { return op_; }
  const Multigrid& multigrid() const { return mg_; }
  const PoissonSolverOptions& options() const { return options_; }
  // Summed over this solver's life (every set-up, solve() and solve_system()).
  const PoissonTimes& times() const { return times_; }

 private:
  PoissonSolverOptions options_;
  PoissonTimes times_;
  PoissonOperator op_;
  Multigrid mg_;
  std::shared_ptr<PoissonSystemSolver> system_;
  Field b_;
  SolveWork work_;
};

}  // namespace finverse::cfd
