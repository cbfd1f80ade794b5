// Evaluation of a batch of scaled parameter vectors in parallel (DESIGN.md section 5.4: "fitness
// evaluations in parallel"). One OpenMP thread per vector at a time (schedule dynamic,1: FEM
// evaluations differ in cost), results stored by index so they do not depend on which thread ran
// what. Each worker limits its own nested parallel regions to one thread, so the FEM's OpenMP
// loops inside an evaluation do not oversubscribe the cores. A single vector (threads = 1) runs
// on the calling thread with the caller's OpenMP settings, so one FEM evaluation can still use
// every core.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fit/parameter_space.hpp"
#include "fit/residual_function.hpp"

namespace finverse::fit {

struct BatchEvaluation {
  std::vector<double> objective;           // distance objective J; +infinity where the model failed
  std::vector<Eigen::VectorXd> residuals;  // when asked for; empty vectors where the model failed
  long failures = 0;                       // evaluations that threw or gave a non-finite value
};

// A std::exception from the residual function (fem::NotConverged, ...) or a non-finite residual
// gives objective +infinity and counts as a failure; fit::Error (bad input, not a bad parameter
// vector) and anything not derived from std::exception is rethrown after the batch.
// In an MPI job (rank_pool.hpp) a batch of two or more vectors of a function the pool knows is
// spread over the ranks; the result is the same.
BatchEvaluation evaluate_batch(const ParameterSpace& space, const ResidualFunction& function,
                               const std::vector<Eigen::VectorXd>& scaled, int threads,
                               bool keep_residuals = false);

// The same on this process's threads only.
BatchEvaluation evaluate_batch_here(const ParameterSpace& space, const ResidualFunction& function,
                                    const std::vector<Eigen::VectorXd>& scaled, int threads,
                                    bool keep_residuals = false);

}  // namespace finverse::fit
