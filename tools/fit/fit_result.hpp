// What one fin-fit run produces, before it is written to materials.h5 (tools/core/CONTRACTS.md):
// every optimiser run's champion and history, the polish from each champion, and the uncertainty
// at the overall optimum. Values are physical unless a name says scaled (z, parameter_space.hpp).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fit/parameter_space.hpp"

namespace finverse::fit {

struct GenerationRecord {
  int generation = 0;        // 1-based
  double best = 0;           // best objective so far in this run
  double mean = 0;           // population mean objective (finite members)
  long evaluations = 0;      // FEM evaluations so far in this run (cache hits not counted)
  double wall_seconds = 0;   // since the run started
  Eigen::VectorXd best_x;    // physical parameters of the best so far
};

struct RunResult {
  std::string method;  // "ga" | "cmaes"
  unsigned seed = 0;
  Eigen::VectorXd best_x;  // physical
  double best_objective = 0;
  std::vector<GenerationRecord> history;
  long evaluations = 0;     // FEM evaluations (cache misses)
  long cache_hits = 0;
  long failures = 0;        // evaluations where the model failed (objective +infinity)
  double wall_seconds = 0;
  bool converged = false;   // the stopping rule (change < tolerance over the window) was met
  // Levenberg-Marquardt polish from best_x (empty when not run).
  Eigen::VectorXd polished_x;
  double polished_objective = 0;       // distance objective at polished_x
  double polished_sum_of_squares = 0;  // |r|^2 at polished_x, what the polish minimises
  long polish_evaluations = 0;
  double polish_wall_seconds = 0;
};

// Gauss-Newton covariance at the optimum in the scaled variables: C = s^2 (J^T J)^-1 with
// s^2 = |r|^2 / (m - n), J = dr/dz (uncertainty.hpp).
struct Uncertainty {
  Eigen::VectorXd standard_error;   // scaled variables (decades for log10 parameters)
  Eigen::VectorXd lower95, upper95; // physical 95 % interval
  Eigen::MatrixXd correlation;
  Eigen::VectorXd singular_values;  // of the weighted Jacobian, descending
  double residual_variance = 0;
  int degrees_of_freedom = 0;
  std::vector<int> identified;      // 1 / 0 per parameter
  std::vector<std::string> verdict; // "identified" | "interval spans more than a decade" | "at bound" | ...
  // The residual's spatial correlation (correlated_residual.hpp), when its layout was known.
  bool systematic_misfit = false;
  double misfit_correlation_length = 0;  // m; 0: white
  double misfit_neighbour_correlation = 0;
  double effective_residuals = 0;
  double effective_channels = 0;  // samples x components that err independently
};

struct FitResult {
  ParameterSpace space;
  std::string objective;            // "dynamic" (eq. 1) | "quasi_static" (eq. 2)
  std::vector<RunResult> runs;
  int best_run = -1;
  Eigen::VectorXd best_x;           // physical, overall best after polish
  double best_objective = 0;        // distance objective [m]
  double best_sum_of_squares = 0;
  Uncertainty uncertainty;
  long evaluations = 0;             // all runs and polishes
  double wall_seconds = 0;
  int threads = 1;
};

}  // namespace finverse::fit
